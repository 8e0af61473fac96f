"""What a folder given to ``worldgen validate`` (or ``drive``) holds: ROS packages, else worlds and specs.

Any folder is searched the way a teaching assistant would look at it: a catkin or colcon workspace (only its
``src/``), a workspace's ``src/``, a metapackage's folder, a folder of students' submissions, nested as deep as it
goes. Packages — catkin ones and ROS 2's ament ones alike — are found as rospack and colcon find them
(:func:`worldgen.core.packages.crawl`: sorted, hidden folders and ``CATKIN_IGNORE``/``COLCON_IGNORE``/
``AMENT_IGNORE`` skipped, not entering a package). A folder holding no package is searched for world files
(``.world``, ``.sdf``), Gazebo model folders and floorplan specs (``.yaml``, ``.yml``, ``.json``) instead; a world
built from a spec beside it (same name) is left out, the spec standing for both. Everything comes back sorted by
path, so the same folder gives the same plan on every machine. The search never leaves the folder: a symlinked
folder in it that leads out (a submission's link to ``/usr/share`` or ``/``) is not followed, and the folder's
note names it. A package the folder holds once (:func:`shared_packages`: the course's world package beside the
submissions) is where every submission's launch files find it.

:func:`shard` takes a stable share of planned items for ``--shard K/N``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Sequence, Tuple, TypeVar

from ..core.errors import InputError
from ..core.findings import Finding
from ..core.packages import MANIFEST, build_type, crawl, manifest_name

WORLD_SUFFIXES = (".world", ".sdf")
SPEC_FILE_SUFFIXES = (".yaml", ".yml", ".json")

T = TypeVar("T")


@dataclass(frozen=True)
class Found:
    """What a folder holds: package folders, or (when it holds none) loose inputs as (kind, path) pairs, kind
    ``world``, ``model-folder`` or ``spec``; ``note`` says it in one line."""

    folder: Path
    packages: Tuple[Path, ...] = ()
    files: Tuple[Tuple[str, Path], ...] = ()
    links_out: Tuple[Path, ...] = ()   # symlinked folders in it leading out of it: not followed
    unpackaged: Tuple[Path, ...] = ()  # its folders that look handed in but hold no package (unpackaged())

    @property
    def note(self) -> str:
        said = self._found()
        if not self.links_out:
            return said
        shown = ", ".join(f"{p} -> {os.path.realpath(p)}" for p in self.links_out[:3])
        more = f" and {len(self.links_out) - 3} more" if len(self.links_out) > 3 else ""
        return (f"{said}; {_count(len(self.links_out), 'folder link')} leading out of it not followed: "
                f"{shown}{more}")

    def _found(self) -> str:
        if self.packages:
            kinds = ["ament" if build_type(p) != "catkin" else "catkin" for p in self.packages]
            counted = [_count(kinds.count(k), f"{k} package") for k in ("catkin", "ament") if kinds.count(k)]
            return f"{self.folder}: {' and '.join(counted)} found"
        if self.files:
            kinds = [k for k, _ in self.files]
            parts = [_count(kinds.count(k), label) for k, label in
                     (("world", "world file"), ("model-folder", "model folder"), ("spec", "spec"))
                     if kinds.count(k)]
            return f"{self.folder}: no catkin package; {', '.join(parts)} found"
        return f"{self.folder}: no catkin package, world or spec found"


def _count(n: int, what: str) -> str:
    return f"{n} {what}{'' if n == 1 else 's'}"


def is_metapackage(folder: str | Path) -> bool:
    """Whether the package in ``folder`` declares ``<export><metapackage/></export>`` (REP 127)."""
    from ..core.safexml import parse_file

    root = parse_file(Path(folder) / MANIFEST)
    return root is not None and root.find("export/metapackage") is not None


def find_packages(folder: Path, outside: list | None = None) -> list[Path]:
    """The catkin packages under ``folder`` (a workspace: under its ``src/``), sorted by path; the walk stays in
    ``folder``, symlinked folders leading out of it going to ``outside``."""
    return sorted(crawl(folder, workspaces=True, limit=10000, outside=[] if outside is None else outside), key=str)


# what a handed-in ROS package holds besides its package.xml (a folder holding none of these is not a submission)
PACKAGE_SIGNS = ("CMakeLists.txt", "*.launch", "*.py")   # (*.py: a node, setup.py, a launch.py)
SPACES = ("build", "devel", "install", "log")   # a workspace's own folders, never a submission


def unpackaged(folder: Path, packages: Sequence[Path]) -> list[Path]:
    """The folders directly in ``folder`` (a class's, one folder a student) that hold no package while others
    do, but hold what a package does (a setup.py, a CMakeLists.txt, a launch file, a node), nothing at all, or
    only archives: a submission whose package.xml is missing, an empty hand-in or a zip nobody unpacked, which a
    crawl for packages would pass over without a word."""
    holding = {Path(p).relative_to(folder).parts[0] for p in packages if Path(p) != folder}
    handed_in = not _source_space(folder)   # a workspace's src/ may hold an empty folder (a submodule not cloned)
    found = []
    for child in sorted(folder.iterdir()):
        if child.name.startswith(".") or child.name in SPACES or child.name in holding or child.is_symlink() \
                or not child.is_dir():
            continue
        if any(next(child.rglob(sign), None) is not None for sign in PACKAGE_SIGNS) or \
                (handed_in and all(_is_archive(f) for f in _files(child))):
            found.append(child)
    return found


def _source_space(folder: Path) -> bool:
    """Whether ``folder`` is a catkin or colcon workspace, or its ``src``: not a class's folder of hand-ins."""
    return folder.name == "src" or any((folder / marker).exists() for marker in
                                       ("CMakeLists.txt", ".catkin_workspace", ".catkin_tools", "src"))


ARCHIVES = (".zip", ".tar", ".tgz", ".gz", ".bz2", ".xz", ".7z", ".rar")


def _files(folder: Path) -> list[Path]:
    """The files under ``folder`` but those hidden (.DS_Store …), at most a few (enough to tell what it holds)."""
    files = []
    for path in folder.rglob("*"):
        if path.is_file() and not any(part.startswith(".") for part in path.relative_to(folder).parts):
            files.append(path)
            if len(files) > 20:
                break
    return files


def _is_archive(path: Path) -> bool:
    return path.suffix.lower() in ARCHIVES


def unpackaged_finding(folder: Path) -> Finding:
    """The row of a handed-in folder that holds no package (:func:`unpackaged`), saying what it holds instead."""
    files = _files(folder)
    if not files:
        return Finding("package", "error", "holds nothing: no package was handed in", where=str(folder),
                       fix="hand the package in (its folder, with its package.xml)")
    if all(_is_archive(f) for f in files):
        return Finding("package", "error", f"holds no package, only {'archives' if len(files) > 1 else 'an archive'}"
                       f" ({files[0].relative_to(folder)})", where=str(folder),
                       fix="unpack it in the folder, so that the package's own folder, with its package.xml, is there")
    return Finding("package", "error", "holds no package: no package.xml in it, so neither catkin nor colcon "
                   "builds it, and roslaunch, rosrun and ros2 cannot find it", where=str(folder),
                   fix="hand the package in with its package.xml (catkin_create_pkg, ros2 pkg create and worldgen "
                       "scaffold write one)")


def find_loose(folder: Path, outside: list | None = None) -> list[tuple[str, Path]]:
    """World files, model folders and specs under ``folder`` (sorted by path); a world with a spec of the same
    name beside it is left out. Symlinked folders are not walked; those leading out of ``folder`` go to
    ``outside``."""
    found: list[tuple[str, Path]] = []
    inside = os.path.join(os.path.realpath(folder), "")
    for dirpath, dirnames, filenames in os.walk(folder):
        here = Path(dirpath)
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        if outside is not None:
            outside += [here / d for d in dirnames if os.path.islink(here / d)
                        and not os.path.join(os.path.realpath(here / d), "").startswith(inside)]
        if here != folder and ((here / "model.config").is_file() and (here / "model.sdf").is_file()):
            found.append(("model-folder", here))
            dirnames.clear()
            continue
        stems = {Path(f).stem for f in filenames if f.lower().endswith(SPEC_FILE_SUFFIXES)}
        for name in sorted(filenames):
            lower = name.lower()
            if name.startswith("."):
                continue
            if lower.endswith(WORLD_SUFFIXES) and Path(name).stem not in stems:
                found.append(("world", here / name))
            elif lower.endswith(SPEC_FILE_SUFFIXES):
                found.append(("spec", here / name))
    return sorted(found, key=lambda item: str(item[1]))


def shared_packages(packages: Sequence[Path]) -> list[Path]:
    """The packages of a graded folder that serve all of it: each whose name no other package there holds (the
    course's world package handed in once beside the students' labs). A launch file's ``$(find PKG)`` looks in
    them after its own workspace and before ``ROS_PACKAGE_PATH``; a name that several submissions hold (each
    student's own copy) is never taken from another student's folder."""
    named = [(manifest_name(Path(p) / MANIFEST) or Path(p).name, Path(p)) for p in packages]
    counts: dict = {}
    for name, _ in named:
        counts[name] = counts.get(name, 0) + 1
    return [p for name, p in named if counts[name] == 1]


DEPEND_TAGS = ("depend", "exec_depend", "run_depend", "build_depend", "build_export_depend")


def depended_on(packages: Sequence[Path]) -> set[str]:
    """The names of the packages that the ``packages`` (metapackages aside: they only group) depend on in their
    package.xml."""
    from ..core.safexml import parse_file

    names: set[str] = set()
    for folder in packages:
        root = parse_file(Path(folder) / MANIFEST)
        if root is None or root.find("export/metapackage") is not None:
            continue
        names.update((el.text or "").strip() for tag in DEPEND_TAGS for el in root.iterfind(tag))
    return names


def search_folder(folder: str | Path) -> Found:
    """:class:`Found` for a folder that is neither a package nor a model folder."""
    folder = Path(folder)
    outside: list = []
    packages = find_packages(folder, outside)
    if packages:
        return Found(folder, tuple(packages), links_out=tuple(sorted(outside, key=str)),
                     unpackaged=tuple(unpackaged(folder, packages)))
    outside = []
    loose = tuple(find_loose(folder, outside))
    return Found(folder, (), loose, tuple(sorted(outside, key=str)))


# ------------------------------------------------------------------------------------------------------ shards

def parse_shard(text: str) -> tuple[int, int]:
    """``K/N`` (1 ≤ K ≤ N) → (K, N); InputError otherwise."""
    try:
        k_text, n_text = text.split("/")
        k, n = int(k_text), int(n_text)
    except ValueError:
        raise InputError(f"bad --shard value {text!r}", hint="write K/N with whole numbers, e.g. 1/4") from None
    if n < 1 or not 1 <= k <= n:
        raise InputError(f"bad --shard value {text!r}: K must be between 1 and N",
                         hint="the shards of N runners are 1/N, 2/N, … N/N")
    return k, n


def shard(items: Sequence[T], k: int, n: int, key: Callable[[T], str]) -> List[T]:
    """Shard ``k`` of ``n`` of ``items``: sorted by ``key`` (a path), every n-th from the (k-1)-th. The share
    depends only on the set of keys, never on the order items come in or on the machine; the n shards are
    disjoint and together hold every item. Items keep their own order within the share."""
    ranked = sorted(range(len(items)), key=lambda i: (key(items[i]), i))
    chosen = {i for rank, i in enumerate(ranked) if rank % n == k - 1}
    return [item for i, item in enumerate(items) if i in chosen]
