"""Property-based: structured but hostile specs, worlds and launch files (hypothesis) never break the contract.

Whatever the document, ``worldgen build``/``validate --skip-sim`` ends with exit 0 or 1 and a verdict, or exit 2
and exactly one line on stderr; never a traceback (an exception escaping the CLI), and nothing written on exit 2.
Examples are derived from a fixed seed (``derandomize``) and bounded in number, so the file runs in well under a
minute and the same way every time.
"""

from __future__ import annotations

import itertools
import os

import pytest
from conftest import CliRunner

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from worldgen.cli import main  # noqa: E402

# HYPO_N=600 HYPO_RANDOM=1 explores more, and differently each run
SETTINGS = settings(max_examples=int(os.environ.get("HYPO_N", "150")), deadline=None,
                    derandomize=not os.environ.get("HYPO_RANDOM"), database=None,
                    suppress_health_check=list(HealthCheck))
_counter = itertools.count()


def holds_contract(result, written) -> None:
    """Exit 0/1 with a verdict on stdout, or exit 2 with one ``worldgen: error:`` line and nothing written."""
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    assert "Traceback" not in result.output
    assert result.exit_code in (0, 1, 2), result.output
    if result.exit_code == 2:
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("worldgen: error: "), result.stderr
        assert not written(), "exit 2 but something was written"
    else:
        assert result.stdout.strip(), "a verdict"


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


@SETTINGS
@given(text=spec_text)
def test_any_spec_gets_a_verdict_or_one_line(tmp_path_factory, text):
    folder = tmp_path_factory.mktemp("spec")
    spec = folder / "t.yaml"
    spec.write_text(text, encoding="utf-8")
    out = folder / f"out{next(_counter)}"
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(out)])
    holds_contract(result, lambda: out.exists() and any(out.iterdir()))


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


@SETTINGS
@given(text=world_text, spawn=st.sampled_from([[], ["--spawn", "0,0"], ["--spawn", "1e6,-1e6,3"]]),
       stl=st.sampled_from(MESH_FILES), obj=st.sampled_from(MESH_FILES))
def test_any_world_gets_a_verdict_or_one_line(tmp_path_factory, text, spawn, stl, obj):
    folder = tmp_path_factory.mktemp("world")
    (folder / "m.stl").write_bytes(stl)
    (folder / "m.obj").write_bytes(obj)
    path = folder / "w.world"
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    junit = folder / "report.xml"
    result = CliRunner().invoke(main, ["validate", "--skip-sim", *spawn, "--junit", str(junit), str(path)])
    holds_contract(result, junit.exists)


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


@SETTINGS
@given(text=launch_text)
def test_any_launch_file_gets_a_verdict_or_one_line(tmp_path_factory, text):
    folder = tmp_path_factory.mktemp("launch")
    (folder / "w.world").write_text("<sdf version='1.6'><world name='w'/></sdf>")
    path = folder / "t.launch"
    path.write_text(text, encoding="utf-8")
    junit = folder / "report.xml"
    result = CliRunner().invoke(main, ["validate", "--skip-sim", "--junit", str(junit), str(path)])
    holds_contract(result, junit.exists)
