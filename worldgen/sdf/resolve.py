"""Where ``model://``, ``package://``, ``file://`` and plain paths in a world point to, the way Gazebo looks them up.

Search order for ``model://NAME/...``: the explicit model paths (``--model-path``), then ``GAZEBO_MODEL_PATH``,
then ``SDF_PATH``, then Gazebo Sim's ``GZ_SIM_RESOURCE_PATH`` and ``IGN_GAZEBO_RESOURCE_PATH`` (all
colon-separated lists of folders holding ``NAME/model.config``), then the
``<gazebo_ros gazebo_model_path="${prefix}/models"/>`` exports of catkin packages on ``ROS_PACKAGE_PATH`` and of
the catkin package that holds the world file itself, and finally a catkin package called NAME
(``model://pkg/meshes/x.dae``).
Nothing is ever fetched from the network: an online (Fuel) URI is named for what it is (:func:`fuel_model`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote

from lxml import etree

from ..core import packages as rospkg
from ..core.safexml import parser

STOCK_MODELS = ("ground_plane", "sun")  # Gazebo's own models, stood in for when no model path has them
MODEL_PATH_VARIABLES = ("GAZEBO_MODEL_PATH", "SDF_PATH", "GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH")
FUEL_HOSTS = ("fuel.gazebosim.org", "fuel.ignitionrobotics.org")


@dataclass(frozen=True)
class Resolved:
    """The outcome of resolving a URI: ``path`` when found, else ``None`` and ``reason`` (what was tried)."""

    uri: str
    path: Path | None
    reason: str = ""
    remote: bool = False

    @property
    def model_name(self) -> str:
        """The model a URI names (``model://NAME/...``; a Fuel URL's ``.../models/NAME[/VERSION]``, spaces
        maybe written ``%20``; else the last part of the path), lower-cased with ``_``."""
        text = self.uri.strip().rstrip("/")
        if text.startswith("model://") and not text.startswith("model:///"):
            name = text[len("model://"):].split("/")[0]
        else:
            parts = unquote(text).split("/")
            name = parts[parts.index("models") + 1] if self.remote and "models" in parts[:-1] else parts[-1]
        return name.strip().lower().replace(" ", "_")


def fuel_model(uri: str) -> tuple[str, str] | None:
    """(owner, model name) of a Gazebo Fuel model URI (``https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground
    Plane[/VERSION]``, spaces maybe written ``%20``), None for any other URI."""
    parts = unquote(uri.strip()).split("/")
    if len(parts) < 7 or parts[0] not in ("http:", "https:") or parts[2].lower() not in FUEL_HOSTS:
        return None
    if parts[5].lower() != "models" or not parts[6].strip():
        return None
    return parts[4], parts[6].strip()


def _split_paths(value: str | None) -> list[Path]:
    return [Path(p) for p in (value or "").split(os.pathsep) if p.strip()]


def model_sdf_file(model_dir: Path) -> tuple[Path | None, str]:
    """The SDF file of a model folder: the highest-version ``<sdf>`` entry of ``model.config``, else ``model.sdf``.

    Returns the file (or None) and a note when something was odd (no model.config, a named file missing).
    """
    config = model_dir / "model.config"
    if config.is_file():
        try:
            root = etree.parse(str(config), parser()).getroot()
            entries = [(e.get("version") or "0", (e.text or "").strip()) for e in root.iterfind("sdf")]
        except (etree.XMLSyntaxError, OSError) as err:
            entries, note = [], f"{config} cannot be read ({err}); used model.sdf"
        else:
            note = ""
        entries = [e for e in entries if e[1]]
        entries.sort(key=lambda e: _version_key(e[0]), reverse=True)
        for _, name in entries:
            if (model_dir / name).is_file():
                return model_dir / name, note
        if entries:
            note = f"{config} names {entries[0][1]}, which does not exist"
    else:
        note = f"{model_dir} has no model.config (Gazebo needs one to find the model)"
    fallback = model_dir / "model.sdf"
    return (fallback if fallback.is_file() else None), note


def _version_key(text: str) -> tuple[int, ...]:
    try:
        return tuple(int(p) for p in text.split("."))
    except ValueError:
        return (0,)


class Resolver:
    """Looks up model folders and resource files for one read. Package crawling happens at most once, lazily."""

    def __init__(self, model_paths=(), *, env=None, world_file: Path | None = None):
        env = os.environ if env is None else env
        self.search = [Path(p) for p in model_paths]
        for variable in MODEL_PATH_VARIABLES:
            self.search += [p for p in _split_paths(env.get(variable)) if p not in self.search]
        self._ros_roots = rospkg.ros_package_path(env)
        self._world_file = world_file
        self._packages: dict[str, Path] | None = None
        self._exported: list[Path] = []

    def _load_packages(self) -> None:
        """Crawl ROS_PACKAGE_PATH, then the package holding the world file: a name's first folder wins (a
        manifest without a readable name counts as its folder's name); model path exports in the same order."""
        if self._packages is not None:
            return
        own = rospkg.owning_package(self._world_file, levels=4) if self._world_file is not None else None
        index = rospkg.PackageIndex(self._ros_roots + ([own] if own is not None else []))
        self._packages = {}
        for folder in index.packages():
            self._packages.setdefault(index.name(folder) or folder.name, folder)
        self._exported = index.model_paths()

    def model_dirs(self) -> list[Path]:
        """Every folder searched for ``model://NAME``, in order."""
        self._load_packages()
        return self.search + self._exported

    def package_dir(self, name: str) -> Path | None:
        self._load_packages()
        assert self._packages is not None
        return self._packages.get(name)

    def _lookup(self, name: str, rest: str, want_dir: bool) -> Path | None:
        """``NAME/rest`` under the search folders (then the env-less package fallbacks)."""
        for base in self.search:  # cheap first: no crawling when the explicit paths have it
            if self._ok(base / name / rest, want_dir):
                return base / name / rest
        for base in self.model_dirs()[len(self.search):]:
            if self._ok(base / name / rest, want_dir):
                return base / name / rest
        package = self.package_dir(name)
        if package is not None and self._ok(package / rest, want_dir):
            return package / rest
        return None

    def where_searched(self) -> str:
        dirs = self.model_dirs()
        return ", ".join(str(d) for d in dirs) if dirs else "no model path is set"

    def resolve(self, uri: str, base_dir: Path, *, want_dir: bool) -> Resolved:
        """Resolve a URI to a model folder (``want_dir``) or a file, relative paths against ``base_dir``."""
        text = uri.strip()
        if text.startswith(("http://", "https://")):
            return Resolved(text, None, "online models are never fetched", remote=True)
        if text.startswith("model:///"):
            path = Path(text[len("model://"):])
            return self._exists(text, path, want_dir)
        for scheme in ("model://", "package://"):
            if text.startswith(scheme):
                name, _, rest = text[len(scheme):].partition("/")
                if not name:
                    return Resolved(text, None, "the URI names no model")
                if scheme == "package://":
                    package = self.package_dir(name)
                    if package is not None and self._ok(package / rest, want_dir):
                        return Resolved(text, package / rest)
                found = self._lookup(name, rest, want_dir)
                if found is not None:
                    return Resolved(text, found)
                return Resolved(text, None, f"no folder '{name}' with '{rest or 'model.config'}' in the model "
                                            f"path ({self.where_searched()})")
        if text.startswith("file://"):
            text = text[len("file://"):]
        path = Path(text).expanduser()
        if not path.is_absolute():
            path = base_dir / path
        return self._exists(uri.strip(), path, want_dir)

    @staticmethod
    def _ok(path: Path, want_dir: bool) -> bool:
        return path.is_dir() if want_dir else path.is_file()

    def _exists(self, uri: str, path: Path, want_dir: bool) -> Resolved:
        if self._ok(path, want_dir) or (want_dir and path.is_file() and path.suffix in (".sdf", ".world")):
            return Resolved(uri, path)
        return Resolved(uri, None, f"{path} does not exist")


MODEL_PATH_FIX = "put the folder that holds it on GAZEBO_MODEL_PATH (or pass --model-path DIR to worldgen)"


def uri_fix(uri: str, resolved: Resolved) -> str:
    """How to make an unresolved model or mesh URI resolvable."""
    if uri.startswith(("model://", "package://")) and not uri.startswith("model:///"):
        return MODEL_PATH_FIX
    if resolved.remote:
        return "download it and refer to it with a model:// URI"
    return ("the path points at a folder on the author's machine: copy the model folder somewhere on "
            "GAZEBO_MODEL_PATH (or --model-path DIR) and refer to it as model://NAME")
