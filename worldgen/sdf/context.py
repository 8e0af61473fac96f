"""What one read of one world carries from function to function: the findings, the model-path resolver, the mesh
cache and the includes being read; and the SDF file being read (its path and version).

Every reading function (:mod:`.models`, :mod:`.shapes`, :mod:`.includes`, :mod:`.state`, :mod:`.emit`) takes the
:class:`ReadContext` as its first argument and reports what it notices through :meth:`ReadContext.note`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Set, Tuple

from lxml import etree

from ..core.findings import Finding, Severity
from ..core.safexml import parse_bytes
from .meshes import MeshCache
from .resolve import Resolver

KNOWN_VERSIONS = ("1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10", "1.11")   # 1.10, 1.11: Gazebo Garden to Ionic


@dataclass
class ReadContext:
    """One read of one world: where it came from, what was noticed, and the caches shared by all its files."""

    source: Path
    resolver: Resolver
    meshes: MeshCache = field(default_factory=MeshCache)
    findings: List[Finding] = field(default_factory=list)
    include_stack: List[Path] = field(default_factory=list)        # the included files being read, outermost first
    missing_meshes: Dict[str, list] = field(default_factory=dict)  # uri -> [reason, fix, where, labels]
    missing_visual_meshes: Dict[str, list] = field(default_factory=dict)   # the same, for visuals' meshes
    unloadable_meshes: Set[str] = field(default_factory=set)       # uris a collision's warning said cannot load
    parsed: Dict[Path, object] = field(default_factory=dict)       # included files: root element, or the error
    include_count: int = 0                                         # includes read so far, at every depth
    pose_texts: Dict[tuple, object] = field(default_factory=dict)  # (text, quat, degrees) → read-only matrix
    mesh_triangles: int = 0                                        # triangles of the meshes placed so far

    @classmethod
    def start(cls, source: Path, model_paths) -> ReadContext:
        """A fresh read of ``source`` (``<string>`` for text), looking up URIs in ``model_paths`` first."""
        return cls(source, Resolver(model_paths, world_file=source if source.name != "<string>" else None))

    def note(self, check: str, severity: Severity, message: str, where: str | None = None,
             fix: str | None = None) -> None:
        self.findings.append(Finding(check, severity, message, where, fix))


@dataclass(frozen=True)
class SdfFile:
    """One SDF file being read: its path (for findings and relative URIs) and SDF version."""

    path: Path
    version: Tuple[int, int]

    @property
    def dir(self) -> Path:
        return self.path.parent

    def where(self, el) -> str:
        return f"{self.path}:{el.sourceline}" if getattr(el, "sourceline", None) else str(self.path)


def parse_sdf(data: bytes, path: Path) -> etree._Element:
    """The root element of SDF bytes; WorldFileError (with the line) when they are not XML."""
    return parse_bytes(data, path, empty_hint="a Gazebo world starts with <sdf version='1.6'>")


def describe_file(ctx: ReadContext, root, path: Path) -> SdfFile:
    """Check the root's SDF version (a finding when odd) and describe the file."""
    text = root.get("version") if root.tag == "sdf" else None
    if root.tag == "sdf" and text is None:
        ctx.note("sdf-version", "warning", "<sdf> has no version attribute; read as SDF 1.6",
                 f"{path}:{root.sourceline}", "write <sdf version='1.6'> (Gazebo 9/11)")
    elif text is not None and text.strip() not in KNOWN_VERSIONS:
        ctx.note("sdf-version", "warning", f"SDF version '{text}' is not one the reader knows "
                 f"({KNOWN_VERSIONS[0]}–{KNOWN_VERSIONS[-1]}); read as the nearest known one",
                 f"{path}:{root.sourceline}", "use version 1.6 for Gazebo Classic 9/11 (ROS Melodic, Noetic, Humble), "
                                              "1.8 to 1.11 for Gazebo Sim (ROS Jazzy)")
    try:
        major, minor = (int(p) for p in (text or "1.6").strip().split(".")[:2])
    except ValueError:
        major, minor = 1, 6
    return SdfFile(path, (major, minor))
