"""catkin packages: ``catkin_create_pkg``-compatible scaffolding for the class.

:func:`package_request` takes catkin_create_pkg's arguments (:class:`PackageArgs`) and gives them the same meaning (defaults, sorting,
the three-tag expansion of each dependency, ``python-*`` system deps as exec_depend only, boost, ``--meta``);
:func:`package_files` renders package.xml (format 2) and a CMakeLists.txt in catkin's skeleton shape, plus the
folders a class package needs (``launch/``, ``worlds/``, ``scripts/``, and ``src/``/``include/NAME`` as catkin
makes them). A package with launch files also exec_depends on gazebo_ros, turtlebot3_description and xacro; one
with a world also has a ``models/`` folder that it exports to Gazebo.
(:func:`worldgen.packages.check.check_package` reads a package back and says what would break.)

Deliberate differences from catkin_create_pkg, each where catkin's output would not work: values are XML-escaped;
``catkin_package()`` lists the catkin dependencies in ``CATKIN_DEPENDS`` (catkin_lint calls it an error when
message packages are missing there) and ``find_package`` leaves out ``message_runtime`` (catkin_lint: it is no
build_depend); a metapackage exec_depends on its members only (REP 127); a maintainer given
as ``"Name <email>"`` or ``"Name email@host"`` keeps that email (catkin would make the invalid
``email@host@todo.todo``), and an author given as ``"Name <email>"`` gets the email.
"""

from __future__ import annotations

import getpass
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Iterable, Mapping, Optional, Sequence, Tuple

from ..core.errors import InputError
from ..launch.writer_xml import default_launch_name, launch_xml
from ..core.resources import render_template
from ..core.fsio import check_free, write_tree
from ..launch.spawn import launch_model, spec_spawn

# REP 144: lowercase letters, digits and underscores, starting with a letter.
PACKAGE_NAME = re.compile(r"^[a-z][a-z0-9_]*$")
BOOST_COMPONENT = re.compile(r"^[A-Za-z0-9_]+$")   # what find_package(Boost COMPONENTS …) names
VERSION = re.compile(r"^(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)$")
# catkin_pkg's rule for an email address
EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")
DEPENDENCY = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]*$")
GAZEBO_DEPENDS = ("gazebo_ros", "turtlebot3_description", "xacro")
ROS2_DISTROS = frozenset({"ardent", "bouncy", "crystal", "dashing", "eloquent", "foxy", "galactic", "humble",
                          "iron", "jazzy", "kilted", "rolling"})


def validate_package_name(name: str) -> str:
    """``name`` if it follows REP 144 (what catkin wants for a new package); InputError otherwise."""
    if not PACKAGE_NAME.match(name or ""):
        raise InputError(f"invalid package name {name!r}",
                         hint="a catkin package name uses lowercase letters, digits and underscores and starts "
                              "with a letter (REP 144), e.g. lab_a_stop_at_wall")
    return name


@dataclass(frozen=True)
class Person:
    name: str
    email: str | None = None


@dataclass(frozen=True)
class PackageRequest:
    """A package as catkin_create_pkg's arguments describe it (already defaulted, sorted and checked)."""

    name: str
    catkin_deps: tuple[str, ...] = ()      # sorted, as given (``catkin`` dropped)
    system_deps: tuple[str, ...] = ()      # as given, ``boost`` appended when boost components are asked for
    boost_comps: tuple[str, ...] = ()
    version: str = "0.0.0"
    description: str = ""
    licenses: tuple[str, ...] = ("TODO",)
    maintainers: tuple[Person, ...] = ()
    authors: tuple[Person, ...] = ()
    meta: bool = False
    exec_only: tuple[str, ...] = ()   # extra exec_depends (the Gazebo packages, a metapackage's members)


def _person(text: str, maintainer: bool) -> Person:
    text = " ".join(str(text).split())
    bracket = re.fullmatch(r"(.*?)\s*<([^<>]+)>", text)
    if bracket:
        name, email = bracket.group(1), bracket.group(2).strip()
    elif maintainer and text and "@" in text.split()[-1] and len(text.split()) > 1:
        name, email = text.rsplit(" ", 1)
    elif maintainer and text:
        name, email = text, f"{text.split()[-1]}@todo.todo"   # catkin_create_pkg's placeholder
    else:
        name, email = text, None
    role = "maintainer" if maintainer else "author"
    if not name:
        raise InputError(f"empty {role} name", hint=f"give the {role} as 'Name' or 'Name <email>'")
    if email is not None and not EMAIL.match(email):
        raise InputError(f"invalid email {email!r} for {role} {name!r}",
                         hint=f"give the {role} as 'Name <you@example.com>'")
    return Person(name, email)


@dataclass(frozen=True)
class PackageArgs:
    """catkin_create_pkg's arguments (and ``worldgen scaffold``'s) as given, before any default or check."""

    name: str
    dependencies: Tuple[str, ...] = ()
    sys_deps: Tuple[str, ...] = ()
    boost_comps: Tuple[str, ...] = ()
    version: Optional[str] = None
    description: Optional[str] = None
    licenses: Tuple[str, ...] = ()
    authors: Tuple[str, ...] = ()
    maintainers: Tuple[str, ...] = ()
    meta: bool = False
    rosdistro: Optional[str] = None


def package_request(args: PackageArgs) -> PackageRequest:
    """catkin_create_pkg's arguments → a checked :class:`PackageRequest`. Raises InputError for an invalid
    package name, version, email, dependency name or a ROS 2 distro."""
    name, version, description, rosdistro = args.name, args.version, args.description, args.rosdistro
    validate_package_name(name)
    if rosdistro and rosdistro.lower() in ROS2_DISTROS:
        raise InputError(f"{rosdistro} is a ROS 2 distro; without --ros worldgen scaffolds catkin (ROS 1) packages",
                         hint="pass --ros humble or --ros jazzy for an ament_python package, or --rosdistro "
                              "noetic")
    version = version or "0.0.0"
    if not VERSION.match(version):
        raise InputError(f"invalid package version {version!r}", hint="use MAJOR.MINOR.PATCH, e.g. 0.1.0")
    description = (description if description is not None else f"The {name} package").strip()
    if not description:
        raise InputError("empty package description", hint="give one with -D, or leave -D out")
    deps = sorted({d for d in args.dependencies if d.lower() != "catkin"})
    system = list(dict.fromkeys(args.sys_deps))
    boost = list(dict.fromkeys(args.boost_comps))
    if boost and "boost" not in system:
        system.append("boost")
    for comp in boost:
        if not BOOST_COMPONENT.match(comp):
            raise InputError(f"invalid boost component {comp!r}",
                             hint="a component is a Boost library name, e.g. -b thread -b system")
    for dep in deps + system:
        if not DEPENDENCY.match(dep):
            raise InputError(f"invalid dependency name {dep!r}", hint="a dependency is a package or rosdep key")
        if dep == name:
            raise InputError(f"the package {name} cannot depend on itself", hint="remove it from the dependencies")
    license_list = sorted(set(args.licenses)) or ["TODO"]
    if any(not lic.strip() for lic in license_list):
        raise InputError("empty license name", hint="give -l a license name such as BSD or MIT")
    maintainer_names = sorted(args.maintainers) or [getpass.getuser()]
    return PackageRequest(
        name=name, catkin_deps=tuple(deps), system_deps=tuple(system), boost_comps=tuple(boost),
        version=version, description=description, licenses=tuple(license_list),
        maintainers=tuple(_person(m, True) for m in maintainer_names),
        authors=tuple(_person(a, False) for a in sorted(args.authors)), meta=args.meta)


def dependency_tags(req: PackageRequest) -> list[tuple[str, str]]:
    """The ``(tag, name)`` dependency elements of package.xml, in catkin_create_pkg's order: buildtool, build,
    build_export, exec; names sorted within each tag."""
    build, export, execute = set(), set(), set(req.exec_only)
    buildtool = {"catkin"}
    for dep in req.catkin_deps:
        if req.meta:
            execute.add(dep)
        elif dep == "genmsg":
            buildtool.add(dep)
        elif dep == "message_generation":
            build.add(dep)
        elif dep == "message_runtime":
            execute.add(dep)
        else:
            build.add(dep), export.add(dep), execute.add(dep)
    for dep in req.system_deps:
        if req.meta or dep.lower().startswith("python-"):
            execute.add(dep)
        else:
            build.add(dep), export.add(dep), execute.add(dep)
    tags = []
    for tag, names in (("buildtool_depend", buildtool), ("build_depend", build),
                       ("build_export_depend", export), ("exec_depend", execute)):
        tags += [(tag, n) for n in sorted(names)]
    return tags


def package_xml(req: PackageRequest, gazebo: bool = False) -> str:
    """package.xml (format 2) for ``req``; ``gazebo`` adds the export of ``models/`` to Gazebo."""
    return render_template("package/package.xml.j2", name=req.name, version=req.version,
                           description=req.description, maintainers=req.maintainers, licenses=req.licenses,
                           authors=req.authors, dependencies=dependency_tags(req), meta=req.meta, gazebo=gazebo)


def cmakelists(req: PackageRequest, data_dirs: Sequence[str] = ()) -> str:
    """CMakeLists.txt in catkin's skeleton shape; ``data_dirs`` are installed to the package's share folder and
    every file in ``scripts/`` (found again at each build, so nodes added later install too) through
    catkin_install_python."""
    # message_runtime is needed at run time only (not by find_package); message_generation at build time only
    components = [d for d in req.catkin_deps if d != "message_runtime"]
    export = [d for d in req.catkin_deps if d not in ("genmsg", "message_generation")]
    system_includes = [d for d in req.system_deps if d != "boost" and not d.lower().startswith("python-")]
    text = render_template("package/CMakeLists.txt.j2", name=req.name, meta=req.meta,
                           catkin_deps=components, boost_comps=req.boost_comps,
                           system_deps=[d for d in req.system_deps if d != "boost"], export_deps=export,
                           system_includes=system_includes, data_dirs=list(data_dirs))
    return text.rstrip("\n") + "\n"


@dataclass
class PackageFiles:
    """A package's files (relative path → text) and which of them are executable."""

    files: dict[str, str]
    executable: set[str] = field(default_factory=set)

    def under(self, prefix: str) -> "PackageFiles":
        """The same package placed in the folder ``prefix`` (for a tree of several packages)."""
        return PackageFiles({f"{prefix}/{k}": v for k, v in self.files.items()},
                            {f"{prefix}/{k}" for k in self.executable})


def package_files(req: PackageRequest, worlds: Mapping[str, str] | None = None,
                  launches: Mapping[str, str] | None = None, scripts: Mapping[str, str] | None = None
                  ) -> PackageFiles:
    """Every file of the package ``req``: package.xml, CMakeLists.txt, ``worlds/NAME`` and ``launch/NAME``
    files, executable ``scripts/NAME``; folders ``launch/``, ``worlds/``, ``scripts/`` (``models/`` with a world),
    ``src/`` for rospy/roscpp and ``include/NAME`` for roscpp. Empty folders hold a ``.gitkeep`` so that git
    keeps them. A metapackage has package.xml and CMakeLists.txt only."""
    worlds, launches, scripts = dict(worlds or {}), dict(launches or {}), dict(scripts or {})
    gazebo = bool(worlds or launches)   # launch files start Gazebo: depend on what they use
    if req.meta:
        if gazebo or scripts:
            raise InputError("a metapackage holds no worlds, launch files or scripts",
                             hint="leave out --meta or --world")
        return PackageFiles({"package.xml": package_xml(req), "CMakeLists.txt": cmakelists(req)})
    if gazebo:
        extra = tuple(d for d in GAZEBO_DEPENDS if d not in req.catkin_deps)
        req = replace(req, exec_only=tuple(sorted(set(req.exec_only) | set(extra))))
    files: dict[str, str] = {}
    files.update({f"worlds/{n}": t for n, t in worlds.items()})
    files.update({f"launch/{n}": t for n, t in launches.items()})
    files.update({f"scripts/{n}": t for n, t in scripts.items()})
    folders = ["launch", "worlds", "scripts"] + (["models"] if worlds else [])
    if "rospy" in req.catkin_deps or "roscpp" in req.catkin_deps:
        folders.append("src")
    if "roscpp" in req.catkin_deps:
        folders.append(f"include/{req.name}")
    for folder in folders:
        if not any(f.startswith(folder + "/") for f in files):
            files[f"{folder}/.gitkeep"] = ""
    data_dirs = [d for d in ("launch", "models", "worlds") if d in folders]   # sorted, as catkin_lint likes
    script_paths = sorted(f"scripts/{n}" for n in scripts)
    files["package.xml"] = package_xml(req, gazebo=bool(worlds))
    files["CMakeLists.txt"] = cmakelists(req, data_dirs)
    return PackageFiles(dict(sorted(files.items())), set(script_paths))


def world_from_spec(spec_path: str | Path, model: str = "optenv") -> tuple[str, str, tuple[float, ...]]:
    """Build the world of the spec at ``spec_path``: its file name ``NAME.world``, its SDF text and the robot's
    spawn pose (x, y, z, yaw): the spec's robot pose, or without one the deepest point of the room."""
    return spec_world(spec_path, model)[:3]


def spec_world(spec_path: str | Path, model: str = "optenv") -> tuple[str, str, tuple[float, ...], str]:
    """:func:`world_from_spec` and the robot model its launch file starts
    (:func:`worldgen.launch.spawn.launch_model`: the spec's robot when the default is asked)."""
    from ..sdf.writer import spec_world_sdf
    from ..spec.load import load_spec

    spec = load_spec(spec_path)
    world_text = spec_world_sdf(spec)
    model = launch_model(spec, model)
    spawn = spec_spawn(spec, world_text, model)
    return f"{spec.name}.world", world_text, spawn, model


def world_package_files(spec_path: str | Path, package: str, model: str = "optenv"
                        ) -> tuple[dict[str, str], dict[str, str]]:
    """(worlds, launches) for a package ``package`` holding the spec's world: ``NAME.world`` and
    ``turtlebot3_in_NAME.launch``."""
    world_file, world_text, spawn, model = spec_world(spec_path, model)
    launch_name = default_launch_name(world_file)
    return ({world_file: world_text},
            {launch_name: launch_xml(world_file, package, model, spawn, launch_name=launch_name)})


def create_package(parent: str | Path, req: PackageRequest, *, world_spec: str | Path | None = None,
                   force: bool = False) -> Path:
    """Write the package ``req`` into ``parent/NAME`` all at once (nothing on error); with ``world_spec`` its
    world and launch file too. An existing folder is refused unless ``force`` (then it is replaced)."""
    target = Path(parent) / req.name
    check_free([target], force)
    worlds = launches = None
    if world_spec is not None:
        if req.meta:
            raise InputError("a metapackage holds no worlds", hint="leave out --meta or --world")
        worlds, launches = world_package_files(world_spec, req.name)
    pkg = package_files(req, worlds, launches)
    return write_tree(target, pkg.files, force=force, executable=pkg.executable)
