"""Property-based: structured but hostile specs, worlds and launch files (hypothesis) never break the contract.

Every document falls in one class, and each class has its exit code:

* the library refuses it with a WorldgenError (a spec that does not load or build; a world or launch file
  ``validate`` cannot plan): bad input, exit 2, exactly one ``worldgen: error:`` line on stderr, nothing written;
* the library reads it and every result passes (a spec that builds always does): exit 0, the report on stdout;
* the library reads it and a result fails (a check found an error): exit 1, the report on stdout.

Never an exception of another kind (a traceback). The work is in the library, so each property runs there on
many examples (:func:`exit_class` is the class); the command line adds the exit code, the one line and the files,
so each property also runs through it on a few examples, which must exit with their class's code.
Examples are derived from a fixed seed (``derandomize``) and bounded in number, so the file runs the same way every
time.
"""

from __future__ import annotations

import itertools
import os

import pytest
from conftest import EXAMPLES, CliRunner
from test_drive import ROOM   # a 3 × 3 m room of four walls

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, event, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from worldgen.check.validate import Options, validate  # noqa: E402
from worldgen.cli import main  # noqa: E402
from worldgen.core.errors import EXIT_BAD_INPUT, EXIT_FAILED, EXIT_OK, WorldgenError  # noqa: E402
from worldgen.core.spawnpose import parse_spawn  # noqa: E402
from worldgen.geometry.building import build_geometry  # noqa: E402
from worldgen.sdf.writer import planned_files  # noqa: E402
from worldgen.spec.load import load_spec  # noqa: E402

# HYPO_N=600 HYPO_RANDOM=1 explores more, and differently each run (HYPO_CLI_N: the command line's examples)
_COMMON = dict(deadline=None, derandomize=not os.environ.get("HYPO_RANDOM"), database=None,
               suppress_health_check=list(HealthCheck))
SETTINGS = settings(max_examples=int(os.environ.get("HYPO_N", "150")), **_COMMON)
CLI_SETTINGS = settings(max_examples=int(os.environ.get("HYPO_CLI_N", "3")), **_COMMON)
_counter = itertools.count()


def exit_class(work, record: bool = True) -> int:
    """The exit code the command line owes a document, from what the library does with it (``work()`` returns
    the results): 2 when the library refuses it with a WorldgenError (whose message is one line), else 0 when every
    result passes, 1 when one fails. Any other exception fails the test. ``record``: count the class in
    hypothesis' statistics (``--hypothesis-show-statistics``)."""
    try:
        results = work()
    except WorldgenError as err:
        assert len(str(err).splitlines()) == 1, str(err)
        code = EXIT_BAD_INPUT
    else:
        code = EXIT_OK if all(r.ok for r in results) else EXIT_FAILED
    if record:
        event(f"exit {code}")
    return code


def holds_contract(result, written, expected: int) -> None:
    """The command exits with its document's class's code: 0/1 with a report on stdout, or 2 with one
    ``worldgen: error:`` line and nothing written; never an exception escaping it."""
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    assert "Traceback" not in result.output
    assert result.exit_code == expected, (expected, result.output)
    if result.exit_code == EXIT_BAD_INPUT:
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("worldgen: error: "), result.stderr
        assert not written(), "exit 2 but something was written"
    else:
        assert result.stdout.strip(), "a report"


def build_spec(spec):
    """``worldgen build SPEC``'s work, without writing: no results to fail, so 0 or 2."""
    planned_files(build_geometry(load_spec(spec)), spec.parent / "out")
    return []


def validate_skip_sim(path, spawn: list[str]):
    """``worldgen validate --skip-sim [--spawn X,Y[,YAW]] PATH``'s results."""
    return validate([path], Options(skip_sim=True, spawn=parse_spawn(spawn[1]) if spawn else None))


# ------------------------------------------------------------------------------------------------- spec YAML

SCALARS = ["2001-13-45", "2001-02-30", "!!int abc", "!!float .", "!!binary a", "!!binary '@@'", "1e999", "-0",
           ".nan", ".inf", "-.inf", "~", "''", "'x'", "!!str", "!!set {a}", "!!omap [a]", "!foo bar",
           "!!python/name:os.system", "9" * 40, "0x1F", "0o17", "1_000", "yes", "no", "on", "&a 1", "*a",
           "&b [1, 2]", "*b", "room", "my_world", "[", "]", "{", "}", "- x", "|", ">", "%TAG", "@", "`", "\\x00",
           "[0, 0]", "[1e308, -1e308]", "[.nan, 1]", "[4, 3]", "{center: [0, 0], size: [4, 3]}",
           "{<<: *b}", "{<<: [*a, *a]}", "[[[[[[[]]]]]]]"]
KEYS = ["name", "walls", "rooms", "robot", "obstacles", "segments", "map", "grid", "when", "x", "<<", "? a",
        "name", "rooms", "lines", "patches"]

room = st.builds(lambda c, s, n: f"  - name: {n}\n    rect: {{center: {c}, size: {s}}}\n",
                 st.sampled_from(["[0, 0]", "[1e9, 0]", "[.nan, 0]", "[a, b]", "[0]", "*a", "[0, 0, 0]"]),
                 st.sampled_from(["[4, 3]", "[0, 3]", "[-4, 3]", "[1e-12, 1e-12]", "[.inf, 1]", "[4]", "4"]),
                 st.sampled_from(["a", "b", "a", "!!int x", "'r'", "[x]"]))
tape = st.builds(lambda p, w, c, k: f"  - {{points: {p}, width: {w}, color: {c}, closed: {k}}}\n",
                 st.sampled_from(["[[0, 0], [1, 0]]", "[[0, 0]]", "[[0, 0], [0, 0]]", "[[0, 0], [1, 0], [0, 0]]", "[]",
                                  "[[.nan, 0], [1, 1]]", "*b", "[[1e9, 0], [0, 0]]", "x", "[[0, 0], [1, 0], [1, 1]]"]),
                 st.sampled_from(["0.05", "0", "-1", "1e-9", "5", ".inf", "x"]),
                 st.sampled_from(["Gazebo/Yellow", "[1, 0, 0]", "[2, 0, 0]", "{rgba: [1, 1]}", "Yelow", "~", "*a"]),
                 st.sampled_from(["true", "false", "yes", "x", "~"]))
patch = st.builds(lambda shape, c: f"  - {{{shape}, color: {c}}}\n",
                  st.sampled_from(["rect: {center: [0, 0], size: [1, 1], yaw: 7}", "rect: {center: [0, 0], size: [1]}",
                                   "disc: {center: [0, 0], radius: 0.2}", "disc: {center: *b, radius: -1}",
                                   "rect: {center: [0, 0], size: [1, 1]}, disc: {center: [0, 0], radius: 1}",
                                   "name: line_0, disc: {center: [0, 0], radius: 0.2}"]),
                  st.sampled_from(["Gazebo/Green", "[0, 1, 0, 0.5]", "7", "~"]))
line = st.one_of(
    st.builds(lambda k, v: f"{k}: {v}\n", st.sampled_from(KEYS), st.sampled_from(SCALARS)),
    st.builds(lambda rooms: "rooms:\n" + "".join(rooms), st.lists(room, min_size=1, max_size=3)),
    st.builds(lambda tapes: "lines:\n" + "".join(tapes), st.lists(tape, min_size=1, max_size=3)),
    st.builds(lambda patches: "patches:\n" + "".join(patches), st.lists(patch, min_size=1, max_size=2)),
    st.builds(lambda t: f"name: {t}\n", st.text(alphabet="ab_\t :#&*!%@[]{}-\n'\"", max_size=12)),
)
spec_text = st.builds(lambda first, rest: first + "".join(rest),
                      st.sampled_from(["name: t\n", "", "%YAML 1.1\n---\n", "---\n", "name: t\nname: u\n"]),
                      st.lists(line, max_size=6))


def _spec(tmp_path_factory, text):
    spec = tmp_path_factory.mktemp("spec") / "t.yaml"
    spec.write_text(text, encoding="utf-8")
    return spec


@SETTINGS
@given(text=spec_text)
def test_any_spec_builds_or_is_refused(tmp_path_factory, text):
    assert exit_class(lambda: build_spec(_spec(tmp_path_factory, text))) in (EXIT_OK, EXIT_BAD_INPUT)


@CLI_SETTINGS
@given(text=spec_text)
def test_build_exits_with_the_specs_class(tmp_path_factory, text):
    spec = _spec(tmp_path_factory, text)
    expected = exit_class(lambda: build_spec(spec))
    out = spec.parent / f"out{next(_counter)}"
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(out)])
    holds_contract(result, lambda: out.exists() and any(out.iterdir()), expected)


# ------------------------------------------------------------------------------------------------- world XML

NUMBERS = ["1 1 1", "0.2 0.2 1", "nan 1 1", "1e308 1e308 1e308", "-1 1 1", "0 0 0", "a b c", "", "1 1",
           "1 1 1 1", "inf 1 1", "1e-300 1 1", "  4  0.1  2 "]
POSES = ["0 0 0 0 0 0", "1 2 0.5 0 0 1.57", "nan 0 0 0 0 0", "1e300 0 0 0 0 0", "0 0 0", "x", "",
         "0 0 0 1e9 1e9 1e9", "0 0 0.5 0 0 0 1"]
URIS = ["model://nope", "model://ground_plane", "model://sun", "file:///dev/zero", "model://../../etc",
        "https://fuel.gazebosim.org/x", "", "package://nope/x", "model://a b"]
MESHES = ["/dev/zero", "nope.stl", "file:///etc/passwd", "", "model://x/meshes/y.dae", "m.stl", "m.obj"]
MATERIALS = ["", "<material><diffuse>1 0 0 1</diffuse></material>", "<material><ambient>nan x</ambient></material>",
             "<material><script><name>Gazebo/Yellow</name></script></material>", "<material><script/></material>",
             "<material><diffuse>2 -1 1e308</diffuse></material>", "<material/>"]
MESH_FILES = [b"", b"solid x\nendsolid x\n", b"\0" * 84, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n# caf\xe9\n",
              b"\0" * 80 + b"\xff\xff\xff\x7f", b"v nan 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 1\n"]


@st.composite
def sdf_element(draw, depth=0):
    kind = draw(st.sampled_from(["box", "cylinder", "sphere", "mesh", "include", "nested", "plane", "junk",
                                 "state", "box"] if depth < 2 else ["box", "cylinder", "include", "junk"]))
    name = draw(st.sampled_from(["a", "b", "a", "wall", "", "x::y", "é"]))
    pose = f"<pose relative_to='{draw(st.sampled_from(['', 'a', 'nope', 'world']))}'>" \
           f"{draw(st.sampled_from(POSES))}</pose>"
    if kind == "include":
        return f"<include><uri>{draw(st.sampled_from(URIS))}</uri><name>{name}</name>{pose}</include>"
    if kind == "nested":
        inner = "".join(draw(st.lists(sdf_element(depth + 1), max_size=2)))
        return f"<model name='{name}'>{pose}{inner}</model>"
    if kind == "junk":
        return draw(st.sampled_from(["<population name='p'><model_count>9</model_count></population>",
                                     "<actor name='x'/>", "<frame name='f' attached_to='nope'/>", "<light/>",
                                     "<model/>", "<link name='l'/>", "<collision><geometry/></collision>"]))
    if kind == "state":
        return f"<state world_name='w'><model name='{name}'>{pose}<scale>0 0 0</scale></model></state>"
    geometry = {
        "box": f"<box><size>{draw(st.sampled_from(NUMBERS))}</size></box>",
        "cylinder": f"<cylinder><radius>{draw(st.sampled_from(NUMBERS))}</radius><length>1</length></cylinder>",
        "sphere": f"<sphere><radius>{draw(st.sampled_from(['0.5', '-1', 'nan', '1e308']))}</radius></sphere>",
        "mesh": f"<mesh><uri>{draw(st.sampled_from(MESHES))}</uri><scale>{draw(st.sampled_from(NUMBERS))}"
                "</scale></mesh>",
        "plane": f"<plane><normal>{draw(st.sampled_from(NUMBERS))}</normal></plane>",
    }[kind]
    static = draw(st.sampled_from(["<static>1</static>", "<static>maybe</static>", ""]))
    material = draw(st.sampled_from(MATERIALS))
    seen = draw(st.sampled_from(["", f"<visual name='v'>{pose}<geometry>{geometry}</geometry>{material}</visual>"]))
    hit = draw(st.sampled_from([f"<collision name='c'>{pose}<geometry>{geometry}</geometry></collision>", ""]))
    return f"<model name='{name}'>{static}{pose}<link name='{name}'>{pose}{hit}{seen}</link></model>"


world_text = st.builds(
    lambda head, version, body, tail: f"{head}<sdf version='{version}'><world name='w'>{''.join(body)}"
                                      f"</world></sdf>{tail}",
    st.sampled_from(["", "<?xml version='1.0'?>\n", "\ufeff", "<!DOCTYPE sdf [<!ENTITY e 'x'>]>", "\n\n"]),
    st.sampled_from(["1.6", "1.4", "2.0", "", "x"]),
    st.lists(sdf_element(), max_size=5),
    st.sampled_from(["", "\n", "<", "&e;", "]]>", "<sdf/>", "\x00"]))


SPAWNS = st.sampled_from([[], ["--spawn", "0,0"], ["--spawn", "1e6,-1e6,3"]])


def _world(tmp_path_factory, text, stl, obj):
    folder = tmp_path_factory.mktemp("world")
    (folder / "m.stl").write_bytes(stl)
    (folder / "m.obj").write_bytes(obj)
    path = folder / "w.world"
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    return path


@SETTINGS
@given(text=world_text, spawn=SPAWNS, stl=st.sampled_from(MESH_FILES), obj=st.sampled_from(MESH_FILES))
def test_any_world_is_judged_or_refused(tmp_path_factory, text, spawn, stl, obj):
    exit_class(lambda: validate_skip_sim(_world(tmp_path_factory, text, stl, obj), spawn))


@CLI_SETTINGS
@given(text=world_text, spawn=SPAWNS, stl=st.sampled_from(MESH_FILES), obj=st.sampled_from(MESH_FILES))
def test_validate_exits_with_the_worlds_class(tmp_path_factory, text, spawn, stl, obj):
    path = _world(tmp_path_factory, text, stl, obj)
    expected = exit_class(lambda: validate_skip_sim(path, spawn))
    junit = path.parent / "report.xml"
    result = CliRunner().invoke(main, ["validate", "--skip-sim", *spawn, "--junit", str(junit), str(path)])
    holds_contract(result, junit.exists, expected)


# ------------------------------------------------------------------------------------------------ launch XML

SUBSTITUTIONS = ["$(find nope)", "$(arg x)", "$(arg nope)", "$(eval 1/0)", "$(eval __import__('os'))",
                 "$(env NOPE_NOPE)", "$(optenv NOPE 1)", "$(anon n)", "$(dirname)", "$(find gazebo_ros)", "$(",
                 "$(arg x", "true", "false", "1", "0", "", "w.world", "$(find worldgen_turtlebot3)/x.world"]


@st.composite
def launch_element(draw, depth=0):
    kind = draw(st.sampled_from(["arg", "include", "node", "param", "group", "rosparam", "junk", "arg"]
                                if depth < 2 else ["arg", "param", "junk"]))
    sub = st.sampled_from(SUBSTITUTIONS)
    if kind == "arg":
        which = draw(st.sampled_from(["default", "value", ""]))
        name = draw(st.sampled_from(["x", "x_pos", "y_pos", "model", "world_name", "x", ""]))
        return f"<arg name='{name}'" + (f" {which}='{draw(sub)}'" if which else "") + "/>"
    if kind == "include":
        inner = "".join(draw(st.lists(launch_element(depth + 1), max_size=2)))
        return f"<include file='{draw(sub)}'>{inner}</include>"
    if kind == "node":
        return (f"<node name='spawn' pkg='gazebo_ros' type='spawn_model' "
                f"args='-urdf -model m -x {draw(sub)} -y 2 -Y 1e9 -param robot_description'/>")
    if kind == "param":
        return f"<param name='robot_description' command='{draw(sub)}' value='{draw(sub)}'/>"
    if kind == "group":
        inner = "".join(draw(st.lists(launch_element(depth + 1), max_size=3)))
        return f"<group {draw(st.sampled_from(['if', 'unless', 'ns']))}='{draw(sub)}'>{inner}</group>"
    if kind == "rosparam":
        return f"<rosparam command='load' file='{draw(sub)}'>{draw(st.sampled_from(SCALARS))}</rosparam>"
    return draw(st.sampled_from(["<machine/>", "<env name='A' value='$(arg x)'/>", "<remap/>", "<test/>",
                                 "<include/>", "<arg/>"]))


launch_text = st.builds(lambda body, tail: f"<launch>{''.join(body)}</launch>{tail}",
                        st.lists(launch_element(), max_size=6), st.sampled_from(["", "<", "<launch/>"]))


def _launch(tmp_path_factory, text):
    folder = tmp_path_factory.mktemp("launch")
    (folder / "w.world").write_text("<sdf version='1.6'><world name='w'/></sdf>")
    path = folder / "t.launch"
    path.write_text(text, encoding="utf-8")
    return path


@SETTINGS
@given(text=launch_text)
def test_any_launch_file_is_judged_or_refused(tmp_path_factory, text):
    exit_class(lambda: validate_skip_sim(_launch(tmp_path_factory, text), []))


@CLI_SETTINGS
@given(text=launch_text)
def test_validate_exits_with_the_launch_files_class(tmp_path_factory, text):
    path = _launch(tmp_path_factory, text)
    expected = exit_class(lambda: validate_skip_sim(path, []))
    junit = path.parent / "report.xml"
    result = CliRunner().invoke(main, ["validate", "--skip-sim", "--junit", str(junit), str(path)])
    holds_contract(result, junit.exists, expected)


# ------------------------------------------------------------------------------------- one document per class

EMPTY_WORLD = "<sdf version='1.6'><world name='w'></world></sdf>"


@pytest.mark.parametrize("kind, text, args, code", [
    ("spec", (EXAMPLES / "enclosed_room.yaml").read_text(), [], EXIT_OK),   # a spec that builds
    ("spec", "rooms: [", [], EXIT_BAD_INPUT),                               # one that does not load
    ("world", ROOM, [], EXIT_OK),                                           # a closed room: every check passes
    ("world", EMPTY_WORLD, [], EXIT_FAILED),                                # no walls round the spawn: one fails
    ("world", ROOM, ["--spawn", "nan,0"], EXIT_BAD_INPUT),                  # a spawn that is no pose
    ("launch", "<launch><arg name='x' default='1'/></launch>", [], EXIT_OK),   # it starts no world: passes
    ("launch", "<launch>", [], EXIT_FAILED),                                # it does not parse: a failed row
])
def test_each_class_has_its_exit_code(tmp_path, kind, text, args, code):
    """The library's class of each document, and the command's exit code, are the ones the docstring gives."""
    path = tmp_path / {"spec": "t.yaml", "world": "w.world", "launch": "t.launch"}[kind]
    path.write_text(text, encoding="utf-8")
    if kind == "spec":
        assert exit_class(lambda: build_spec(path), record=False) == code
        out = tmp_path / "out"
        holds_contract(CliRunner().invoke(main, ["build", str(path), "-o", str(out)]), out.exists, code)
    else:
        assert exit_class(lambda: validate_skip_sim(path, args), record=False) == code
        junit = tmp_path / "report.xml"
        result = CliRunner().invoke(main, ["validate", "--skip-sim", *args, "--junit", str(junit), str(path)])
        holds_contract(result, junit.exists, code)
