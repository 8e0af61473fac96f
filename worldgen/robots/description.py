"""Robot descriptions: a TurtleBot3 model name or a user's ``.urdf.xacro``/``.urdf`` file → URDF text.

Our own TurtleBot3 descriptions live in the ROS package folder ``worldgen_turtlebot3`` (see
:func:`worldgen.core.resources.robots_dir`). xacro (PyPI) resolves ``$(find pkg)`` through ament only, so while a file
is processed its resolver is swapped for one that walks ``ROS_PACKAGE_PATH`` (and our robots folder) for a
``package.xml`` with that ``<name>`` — which is how ROS 1 finds packages, so the real ``turtlebot3_description``
works too when it is on the path. :func:`absolute_mesh_paths` turns ``package://`` URIs into file paths, since
pybullet only looks beside the URDF file for them.
"""

from __future__ import annotations

import functools
import os
import re
import threading
from pathlib import Path

from ..core import packages as rospkg
from ..core.errors import InputError, WorldFileError
from ..core.inputs import check_regular, read_capped
from ..core.resources import ROBOT_MODELS, robots_dir
from ..core.safexml import parse_bytes

MODELS = ROBOT_MODELS   # the TurtleBot3 models we describe
_XACRO_LOCK = threading.Lock()  # xacro keeps its state in module globals


class PackageNotFound(LookupError):
    """``$(find pkg)`` named a package that no folder on the search path holds."""

    def __init__(self, name: str):
        super().__init__(name)
        self.name = name


def package_search_path() -> list[Path]:
    """Folders searched for ROS packages: ``ROS_PACKAGE_PATH`` (in order), then worldgen's robots folder."""
    return rospkg.ros_package_path() + [robots_dir().parent]


def find_package(name: str) -> Path:
    """The folder of ROS package ``name``: the first folder under the search path whose ``package.xml`` says
    ``<name>name</name>``. ``ROOT`` and ``ROOT/name`` of every root are tried first; then the roots are crawled
    in order as rospack does (:func:`worldgen.core.packages.crawl`). Raises :class:`PackageNotFound`; a package once
    found is remembered for the same search path."""
    roots = tuple(package_search_path())
    key = (roots, name)
    if key not in _FOUND:
        _FOUND[key] = _search(rospkg.PackageIndex(roots), name)
    return _FOUND[key]


_FOUND: dict[tuple[tuple[Path, ...], str], Path] = {}


def _search(index: rospkg.PackageIndex, name: str) -> Path:
    for root in index.roots:
        for guess in (root, root / name):
            if index.name(guess) == name:
                return guess
    for folder in index.packages():
        if index.name(folder) == name:
            return folder
    raise PackageNotFound(name)


def robot_file(robot: str | Path) -> Path:
    """A model name (``burger``, ``waffle``, ``waffle_pi``) → our xacro file; anything else is a path that must
    exist and end in ``.xacro`` or ``.urdf``."""
    text = str(robot)
    if text in MODELS:
        return robots_dir() / "urdf" / f"turtlebot3_{text}.urdf.xacro"
    path = Path(text).expanduser()
    if not (text.endswith((".xacro", ".urdf")) or os.sep in text):
        raise InputError(f"unknown robot {text!r}",
                         hint=f"use one of {', '.join(MODELS)} or the path of a .urdf or .urdf.xacro file")
    if not path.is_file():
        raise InputError("robot description not found", path=path,
                         hint=f"give an existing .urdf or .urdf.xacro file, or one of {', '.join(MODELS)}")
    return path.resolve()


def robot_urdf(robot: str | Path = "burger", mappings: dict[str, str] | None = None) -> str:
    """The URDF text of ``robot`` (a model name or a file path).

    ``.urdf`` files are returned as they are; anything else goes through ``xacro.process_file`` with
    ``mappings`` as its ``name:=value`` arguments and ``$(find pkg)`` resolved by :func:`find_package`.
    Errors (missing file or package, xacro or XML errors) become :class:`InputError` naming the file.
    """
    path = robot_file(robot)
    check_regular(path, InputError, "robot description")
    if path.suffix == ".urdf":
        try:
            text = read_capped(path, error=InputError, what="robot description").decode("utf-8")
            parse_bytes(text.encode("utf-8"), path, hint="fix the URDF file (it must be well-formed XML)")
        except (OSError, UnicodeDecodeError) as err:
            raise InputError(f"cannot read the robot description: {err}", path=path,
                             hint="fix the URDF file (it must be well-formed XML)") from None
        except WorldFileError as err:
            raise InputError(f"cannot read the robot description: {err.message}", path=path, line=err.line,
                             hint=err.hint) from None
        return text
    if mappings is None and robot in MODELS:
        return _model_urdf(str(robot))
    return _xacro_urdf(path, dict(mappings or {}))


@functools.lru_cache(maxsize=None)
def _model_urdf(model: str) -> str:
    """Our own description of ``model``, processed once per process (the files ship with worldgen)."""
    return _xacro_urdf(robot_file(model), {})


def _xacro_urdf(path: Path, mappings: dict[str, str]) -> str:
    """xacro's output for ``path``, kept on disk while what it was made from is unchanged (:mod:`.cache`)."""
    from .cache import cached_urdf

    return cached_urdf(path, mappings, package_search_path(), find_package,
                       lambda inputs: _process_xacro(path, mappings, inputs), code=__file__)


def _process_xacro(path: Path, mappings: dict[str, str], inputs=None) -> str:
    """``xacro.process_file`` with ``$(find)`` ours; ``inputs`` (a :class:`.cache.Inputs`) records the files,
    environment variables and packages it read."""
    import xml.parsers.expat

    import xacro
    import xacro.substitution_args as sa

    def resolve(pkg: str) -> str:
        found = str(find_package(pkg))
        if inputs is not None:
            inputs.packages[pkg] = found
        return found

    def env(name: str) -> str:
        if inputs is not None:
            inputs.env[name] = os.environ.get(name)
        return saved_env(name)

    def optenv(name: str, default: str = "") -> str:
        if inputs is not None:
            inputs.env[name] = os.environ.get(name)
        return saved_optenv(name, default)

    with _XACRO_LOCK:
        saved = sa._eval_find, sa._eval_dict["find"]
        saved_env, saved_optenv = sa._eval_env, sa._eval_optenv
        sa._eval_find = sa._eval_dict["find"] = resolve
        sa._eval_env = sa._eval_dict["env"] = env
        sa._eval_optenv = sa._eval_dict["optenv"] = optenv
        xacro.all_includes = []   # the files it opens besides ``path`` (xacro keeps them in a module global)
        try:
            doc = xacro.process_file(str(path), mappings=mappings)
            for included in xacro.all_includes if inputs is not None else ():
                inputs.add_file(included)
        except xacro.XacroException as err:
            raise _xacro_error(path, err) from None
        except (xml.parsers.expat.ExpatError, OSError) as err:
            raise InputError(f"xacro cannot read the robot description: {err}", path=path,
                             hint="fix the file (it must be well-formed XML)") from None
        except RecursionError:
            raise InputError("xacro recursed without end", path=path,
                             hint="an include or a macro calls itself: break the cycle") from None
        finally:
            sa._eval_find, sa._eval_dict["find"] = saved
            sa._eval_env = sa._eval_dict["env"] = saved_env
            sa._eval_optenv = sa._eval_dict["optenv"] = saved_optenv
    return doc.toprettyxml(indent="  ")


def _xacro_error(path: Path, err: Exception) -> InputError:
    cause = getattr(err, "exc", None)
    if isinstance(cause, PackageNotFound):
        searched = os.pathsep.join(str(p) for p in package_search_path())
        return InputError(f"xacro: $(find {cause.name}): no package named {cause.name!r}", path=path,
                          hint=f"add the folder holding it to ROS_PACKAGE_PATH (searched: {searched})")
    where = getattr(err, "filename", None)
    return InputError(f"xacro failed: {err}", path=where or path,
                      hint="fix the xacro file or pass its arguments (name:=value) as mappings")


_PACKAGE_URI = re.compile(r"package://([^/\"'<>\s]+)/")


def absolute_mesh_paths(urdf: str, source: str | Path | None = None) -> str:
    """``urdf`` with every ``package://pkg/rest`` URI replaced by the absolute path of ``rest`` in package
    ``pkg`` and ``file://`` prefixes dropped, so pybullet finds the files wherever the URDF is written.
    An unknown package is an :class:`InputError` (naming ``source``)."""
    def replace(match: re.Match) -> str:
        try:
            return str(find_package(match.group(1))) + "/"
        except PackageNotFound:
            raise InputError(f"mesh path {match.group(0)}… names a package that is not on ROS_PACKAGE_PATH",
                             path=source, hint=f"add the folder holding {match.group(1)} to ROS_PACKAGE_PATH"
                             ) from None

    return _PACKAGE_URI.sub(replace, urdf).replace("file://", "")
