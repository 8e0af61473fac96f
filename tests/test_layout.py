"""The package's folders are its design: imports run one way between them, and nothing imports in a circle.

The graph is read from the source (ast), with imports inside functions counted too: a lazy import is still a
dependency, only a cheaper one. The build path's import-time closure is checked separately, in a fresh process.
"""

from __future__ import annotations

import ast
import functools
import json
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "worldgen"

# Each part may import only parts of a lower layer (and itself). The README's design section draws these layers.
LAYERS = {
    "core": 0,
    "spec": 1,
    "geometry": 2, "robots": 2,
    "sdf": 3,
    "pyread": 3,     # reading Python without running it (launch.py, setup.py); imports core only
    "generate": 3,   # seeded floorplan specs (mazes, apartments, clutter, arenas, tracks)
    "sim": 4,
    "launch": 4,     # launch files of ROS 1 and ROS 2: the model, the readers, the writers
    "runtime": 4,    # students' nodes' runtime: what they import, whether it is installed, doctor
    "packages": 5,   # catkin and ament packages: scaffold, course, checks (they write and read launch files)
    "check": 6, "interface": 6,   # interface: what each robot publishes and takes, described once as data
    "view": 7, "bridge": 7,   # bridge: runs, rubrics and reports; view: pictures and pages of worlds and runs
    "ros1": 8, "ros2": 8,     # the transports: ROS 1 (rospy), ROS 2 (DDS)
    "cli": 9,
    "": -1,         # worldgen/__init__.py: the version, importing nothing
    "__main__": 10,  # python -m worldgen
}
# The parts of the package's root, as the README's design section draws them.
PARTS = ("core", "spec", "geometry", "robots", "sdf", "pyread", "generate", "sim", "launch", "runtime", "packages", "check",
         "interface", "view", "bridge", "ros1", "ros2", "cli")
MAX_MODULES = 18   # a part one can learn in a day
# The parts that speak ROS, and ROS's own client libraries: the simulation reaches none of them.
ROS_PARTS = ("launch", "packages", "runtime", "ros1", "ros2")
ROS_LIBRARIES = ("rospy", "rosgraph", "rosbag", "rclpy", "cyclonedds")
WRITERS = ("worldgen.sdf.writer", "worldgen.sdf.gzsim", "worldgen.launch.writer_xml", "worldgen.launch.writer_py",
           "worldgen.launch.gz_bridge_params", "worldgen.packages.catkin", "worldgen.packages.ament",
           "worldgen.packages.world_files", "worldgen.packages.course_ros1", "worldgen.packages.course_ros2")
# The launch-file readers never reach a writer: what both share lives in worldgen.launch.model.
LAUNCH_READERS = ("worldgen.launch.reader", "worldgen.launch.reader_py", "worldgen.launch.walk_xml",
                  "worldgen.launch.params_xml", "worldgen.launch.substitution_xml", "worldgen.launch.scope_py",
                  "worldgen.launch.values_py", "worldgen.launch.gazebo_py")
BUILD_PATH = ("worldgen.spec.load", "worldgen.geometry.building", "worldgen.sdf.writer")
HEAVY = ("pybullet", "trimesh", "shapely")


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path, top_level_only: bool = False) -> set[str]:
    """The modules ``path`` imports (worldgen modules by full name; others by their top-level name)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    nodes = tree.body if top_level_only else list(ast.walk(tree))
    found = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found.add(target)
            for alias in node.names:   # "from . import build": build is a module
                if (PACKAGE.parent / Path(*f"{target}.{alias.name}".split("."))).with_suffix(".py").exists() or \
                        (PACKAGE.parent / Path(*f"{target}.{alias.name}".split(".")) / "__init__.py").exists():
                    found.add(f"{target}.{alias.name}")
    found.discard(name)   # "from . import build" in a package's __init__ names its modules, not itself
    return {m if m.startswith("worldgen") else m.split(".")[0] for m in found if m}


@functools.lru_cache(maxsize=None)   # read once per session: every test below walks the same graph
def graph(top_level_only: bool = False) -> dict[str, set[str]]:
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    return {name: {m for m in _imports(path, top_level_only) if m in modules or not m.startswith("worldgen")}
            for name, path in modules.items()}


def part(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def cycles(g: dict[str, set[str]]) -> list[list[str]]:
    """Every strongly connected set of more than one module (or a module importing itself), Tarjan's way."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in g.get(v, ()):
            if w not in g:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1 or v in g.get(v, ()):
                found.append(sorted(component))

    for v in sorted(g):
        if v not in index:
            visit(v)
    return found


def closure(g: dict[str, set[str]], start: str, packages: bool = False) -> set[str]:
    """Every module ``start`` reaches in ``g``; with ``packages``, each one's parent packages too (their
    ``__init__``, which importing a module runs)."""
    seen, todo = set(), [start]
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        todo.extend(g.get(m, ()))
        if packages:
            parts = m.split(".")
            todo.extend(".".join(parts[:i]) for i in range(2, len(parts)) if ".".join(parts[:i]) in g)
    return seen


def test_every_part_is_in_a_layer():
    parts = {part(m) for m in graph()}
    assert parts <= set(LAYERS), f"parts with no layer: {sorted(parts - set(LAYERS))}"


def test_root_reads_as_the_design():
    """The package's root is its parts, one folder each, as the README draws them: nothing else beside
    ``__init__.py``/``__main__.py``, and every part in a layer."""
    entries = {p.name for p in PACKAGE.iterdir() if not p.name.startswith("__") and p.name != "py.typed"}
    assert entries <= set(PARTS), sorted(entries - set(PARTS))
    assert set(PARTS) <= set(LAYERS)


def test_no_part_has_more_than_eighteen_modules():
    big = {}
    for folder in (p for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()):
        modules = [p for p in folder.rglob("*.py") if p.name != "__init__.py"]
        if len(modules) > MAX_MODULES:
            big[folder.name] = len(modules)
    assert big == {}


def test_the_launch_readers_never_reach_a_writer():
    g = graph()
    for module in LAUNCH_READERS:
        reached = closure(g, module)
        assert not reached.intersection(WRITERS), (module, sorted(reached.intersection(WRITERS)))


def test_no_module_imports_in_a_circle():
    assert cycles(graph()) == []


def test_imports_run_down_the_layers_only():
    wrong = []
    for module, imported in graph().items():
        for target in imported:
            if target.startswith("worldgen") and part(target) != part(module) and \
                    LAYERS[part(target)] >= LAYERS[part(module)]:
                wrong.append(f"{module} → {target}")
    assert wrong == []


def test_the_simulation_never_reaches_a_writer():
    g = graph()
    for module in (m for m in g if part(m) == "sim"):
        reached = closure(g, module)
        assert not reached.intersection(WRITERS), (module, sorted(reached.intersection(WRITERS)))


def test_the_build_path_imports_nothing_heavy_at_import_time():
    g = graph(top_level_only=True)
    for module in BUILD_PATH:
        assert not closure(g, module).intersection(HEAVY), module
    code = (f"import sys, json; import {', '.join(BUILD_PATH)}; "
            f"print(json.dumps(sorted(m for m in {list(HEAVY)!r} if m in sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=PACKAGE.parent).stdout
    assert json.loads(out) == []


@pytest.mark.parametrize("bad", [
    {"worldgen.a.x": {"worldgen.a.y"}, "worldgen.a.y": {"worldgen.a.x"}},
    {"worldgen.a.x": {"worldgen.a.x"}},
])
def test_the_circle_finder_finds_circles(bad):
    assert cycles(bad)


def test_no_module_is_over_600_lines_nor_a_class_over_250():
    long = []
    for path in PACKAGE.rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        if text.count("\n") > 600:
            long.append(f"{path.name}: {text.count(chr(10))} lines")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ClassDef) and node.end_lineno - node.lineno + 1 > 250:
                long.append(f"{path.name}: class {node.name} {node.end_lineno - node.lineno + 1} lines")
    assert long == []


def test_the_simulation_never_imports_ros():
    g = graph()
    for module in (m for m in g if part(m) == "sim"):
        reached = closure(g, module)
        ros = sorted(m for m in reached if m.split(".")[0] in ROS_LIBRARIES
                     or (m.startswith("worldgen.") and part(m) in ROS_PARTS))
        assert ros == [], module


def test_the_bridge_and_the_view_do_not_import_each_other():
    g = graph()
    for module, imported in g.items():
        if part(module) in ("bridge", "view"):
            other = {"bridge": "view", "view": "bridge"}[part(module)]
            assert not [m for m in imported if m.startswith("worldgen") and part(m) == other], module


def test_each_folder_is_one_layer():
    """Every folder of the package is one part with one layer: no module sits a layer above the rest of its
    folder (the live bridge once lived beside the launch-file readers and writers, a layer above them)."""
    for folder in (p for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()):
        assert folder.name in LAYERS, folder
        nested = [p for p in folder.rglob("__init__.py") if p.parent != folder]
        assert nested == [], f"{folder.name} holds sub-packages {nested}: give each its own part"


MAX_PARAMETERS = 8   # more, and a call site cannot be read: pass one options value instead (see check/validate.Options)
# Functions outside cli/ allowed more than MAX_PARAMETERS, each with its reason: "module.function" → why.
MANY_PARAMETERS: dict[str, str] = {
    # none today; a function in a file being rewritten by the ROS 2 work goes here, with that reason
}


def parameter_count(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Positional and keyword-only parameters, not ``self``/``cls``; ``*args`` and ``**kwargs`` count one each."""
    args = node.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    count = len(names) - (1 if names and names[0] in ("self", "cls") else 0)
    return count + (args.vararg is not None) + (args.kwarg is not None)


def test_no_function_outside_the_cli_takes_more_than_eight_parameters():
    """Options travel as values (one frozen dataclass a command builds), not as long lists of parameters; only
    a click command, whose parameters are its options, may take more."""
    long = {}
    for path in PACKAGE.rglob("*.py"):
        if part(module_name(path)) == "cli":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and parameter_count(node) > MAX_PARAMETERS:
                long[f"{module_name(path)}.{node.name}"] = parameter_count(node)
    assert {k: v for k, v in long.items() if k not in MANY_PARAMETERS} == {}
    assert sorted(set(MANY_PARAMETERS) - set(long)) == [], "allowed but no longer long: take it off the list"


def test_the_parameter_count_counts_what_a_caller_writes():
    tree = ast.parse("class A:\n def f(self, a, b=1, *rest, c, **more): pass\ndef g(a, /, b): pass\n")
    counts = {n.name: parameter_count(n) for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
    assert counts == {"f": 5, "g": 2}


# ------------------------------------------------------------------------------------ imports where a reader sees them

# Third-party modules a worldgen module may import inside a function, so that a command that does not use one does
# not pay for it at start-up: each with what it costs (python -X importtime, 2-core machine) or why it may be absent.
LAZY_THIRD_PARTY = {
    "pybullet": "150 ms", "trimesh": "390 ms", "shapely": "150 ms", "matplotlib": "370 ms",
    "mpl_toolkits": "matplotlib's", "scipy": "190 ms", "numpy": "200 ms", "jinja2": "60 ms", "lxml": "25 ms",
    "yaml": "21 ms", "moderngl": "an OpenGL context", "PIL": "the camera's and the pictures' only",
    "cyclonedds": "the ros2 extra (Python 3.10+)", "rosbags": "a test extra", "playwright": "the browser tests'",
    "xacro": "robot files only", "catkin_pkg": "a test extra",
    # ROS's own, never installed with worldgen: Debian's ROS 1 Python, a peer's rclpy
    "rospy": "ROS 1", "rosgraph": "ROS 1", "rosbag": "ROS 1", "roslaunch": "ROS 1", "roslib": "ROS 1",
    "rospkg": "ROS 1", "genpy": "ROS 1", "std_msgs": "ROS 1", "geometry_msgs": "ROS 1", "sensor_msgs": "ROS 1",
    "nav_msgs": "ROS 1", "gazebo_msgs": "ROS 1", "tf2_msgs": "ROS 1", "rosgraph_msgs": "ROS 1", "std_srvs": "ROS 1",
    "rclpy": "ROS 2",
}
# worldgen modules imported inside a function although they bring none of those, each for a measured reason:
# (importing module, imported module) → why.
LAZY_WORLDGEN = {
    ("worldgen.bridge.world", "worldgen.launch.reader"):
        "a launch file's world only: the readers and pyread, 16 modules `worldgen --help` and every run would load",
    ("worldgen.ros1.nodes", "worldgen.launch.reader"):
        "launch files among the nodes only: the same 16 modules",
    ("worldgen.launch.reader", "worldgen.launch.reader_py"):
        "a ROS 2 launch.py only: the Python reader and pyread, 25 ms that validate of a roslaunch XML file would pay",
    ("worldgen.view.vendor", "worldgen.core.errors"):
        "the build hook loads vendor.py by its path, alone, where no relative import at module level can work",
}
# Modules whose in-function imports are left as they are while others rewrite them: module → why.
IMPORTS_LEFT = {
    **{m: "ROS 2 work in progress" for m in (
        "worldgen.generate", "worldgen.cli.run", "worldgen.cli.sim", "worldgen.cli.generate", "worldgen.cli",
        "worldgen.core.packages", "worldgen.geometry.mesh_section", "worldgen.core.labels",
        "worldgen.core.numbers", "worldgen.view.scene_data", "worldgen.check.validate")},
    **{m: "being rewritten by another helper right now (fork server, robot cache, stop-at-wall until still, "
          "the simulators' start)" for m in (
        "worldgen.sim.process", "worldgen.sim.forkserver", "worldgen.sim.session", "worldgen.sim.behaviours",
        "worldgen.sim.scene_loader", "worldgen.sim.quiet", "worldgen.check.sim_job", "worldgen.check.sim_run",
        "worldgen.core.resources", "worldgen.robots.description", "worldgen.robots.cache", "worldgen.cli.validate",
        "worldgen.ros1.simcmd", "worldgen.ros1.rosenv", "worldgen.ros1.ready", "worldgen.ros1.__main__",
        "worldgen.runtime.interpreters")},
}
# cli/ modules are the commands: each imports what it runs inside the command, so that `worldgen --help` (which lists
# every command) and each command load only what that command runs (measured: moved to the top, `worldgen --help`
# loaded 55 more worldgen modules, +300 ms, and `worldgen doctor --help` 81 more, +180 ms).
COMMANDS_PART = "cli"
# The program's entry forks validate's simulation server before click, the checks or the readers are imported (the
# server imports its share on the other core: bench_speed.py), so each of its imports is made at its moment.
ENTRY = "worldgen.__main__"


def late_imports(path: Path) -> list[tuple[int, str]]:
    """(line, module) of every worldgen module ``path`` imports inside a function."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for func in (n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))):
        for node in ast.walk(func):
            targets = []
            if isinstance(node, ast.ImportFrom):
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)] if node.level else []
                target = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module or ""
                targets = [target] + [f"{target}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            modules = graph()
            for target in dict.fromkeys(t for t in targets if t.startswith("worldgen") and t in modules):
                found.append((node.lineno, target))
    return sorted(set(found))


def test_worldgen_modules_are_imported_at_the_top():
    """A reader sees a module's imports at its top: worldgen's own modules are imported there, unless the import
    brings, when it runs, a third-party module of LAZY_THIRD_PARTY that the importing module does not import
    already, or the command modules (COMMANDS_PART), or LAZY_WORLDGEN and IMPORTS_LEFT say why not."""
    top = graph(top_level_only=True)
    late = []
    for path in sorted(PACKAGE.rglob("*.py")):
        module = module_name(path)
        if part(module) == COMMANDS_PART or module == ENTRY or any(module == m or module.startswith(m + ".")
                                                                   for m in IMPORTS_LEFT):
            continue
        own = {m.split(".")[0] for m in closure(top, module, packages=True)}
        for line, target in late_imports(path):
            brings = {m.split(".")[0] for m in closure(top, target, packages=True)} - own
            if not brings & set(LAZY_THIRD_PARTY) and (module, target) not in LAZY_WORLDGEN:
                late.append(f"{path.relative_to(PACKAGE.parent)}:{line} imports {target} in a function")
    assert late == []


def test_what_is_left_lazy_is_still_there():
    """Every entry of LAZY_WORLDGEN is an import that is still made inside a function."""
    made = {(module_name(p), target) for p in PACKAGE.rglob("*.py") for _, target in late_imports(p)}
    assert sorted(set(LAZY_WORLDGEN) - made) == []


def test_the_start_order_names_modules_that_exist():
    """conftest's LONGEST_FIRST (the parallel run's start order) names test modules that are there, once each."""
    from conftest import LONGEST_FIRST

    here = {p.name for p in Path(__file__).parent.glob("test_*.py")}
    assert sorted(set(LONGEST_FIRST) - here) == [] and len(set(LONGEST_FIRST)) == len(LONGEST_FIRST)
