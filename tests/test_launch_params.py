"""The parameters, remaps and environment a launch file gives its nodes, read as roslaunch reads them: typed
values, private `~` names, `<rosparam>` files and inline YAML, `<group ns>` and included files; and the same
parameters as roslaunch's own loader (Debian's python3-roslaunch) finds in a file that uses every form."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rosstubs import need_module, roslaunch_load, ros_env
from worldgen.launch.params_xml import ParamError, param_name, rosparam_sets, set_value, typed_value
from worldgen.launch.reader import read_launch


@pytest.mark.parametrize("text, kind, expected", [
    ("10", None, 10), ("0.5", None, 0.5), ("1e3", None, "1e3"), ("-2", None, -2), ("True", None, True),
    (" false ", None, False), ("hello", None, "hello"), ("12", "str", "12"), ("1", "double", 1.0),
    ("0", "bool", False), ("TRUE", "boolean", True), ("[1, 2]", "yaml", [1, 2]), ("7", "int", 7),
])
def test_values_are_typed_as_roslaunch_types_them(text, kind, expected):
    value = typed_value(text, kind)
    assert value == expected and type(value) is type(expected)


@pytest.mark.parametrize("text, kind", [("one", "int"), ("x", "double"), ("yes", "bool"), ("1", "float")])
def test_a_value_not_of_its_type_is_refused(text, kind):
    with pytest.raises(ParamError):
        typed_value(text, kind)


def test_names_land_where_roslaunch_puts_them():
    assert param_name("rate", "/robot1", None) == "/robot1/rate"
    assert param_name("~rate", "/robot1", "/robot1/driver") == "/robot1/driver/rate"
    assert param_name("rate", "/robot1", "/robot1/driver") == "/robot1/driver/rate"
    assert param_name("/rate", "/robot1", "/robot1/driver") == "/rate"
    with pytest.raises(ParamError, match="outside a <node>"):
        param_name("~rate", "/", None)


def test_rosparam_documents_and_later_values():
    assert rosparam_sets({"a": 1, "b": {"c": 2}}, "/ns", None) == [("/ns/a", 1), ("/ns/b", {"c": 2})]
    assert rosparam_sets([1, 2], "/ns", "/ns/list") == [("/ns/list", [1, 2])]
    with pytest.raises(ParamError, match="mapping"):
        rosparam_sets([1, 2], "/ns", None)
    params = {"/a/b": 1, "/a/c": 2, "/ab": 3}
    set_value(params, "/a", {"d": 4, "b": 5})        # a mapping is unrolled into leaves: they merge, as on the master
    assert params == {"/a/c": 2, "/ab": 3, "/a/d": 4, "/a/b": 5}
    set_value(params, "/a", 7)                        # a plain value replaces the whole subtree
    assert params == {"/ab": 3, "/a": 7}


@pytest.mark.parametrize("text, expected", [
    ("!radians pi/2", math.pi / 2), ("!degrees 90", math.pi / 2), ("!degrees deg(90)", math.pi / 2),
    ("rad(pi/4)", math.pi / 4), ("deg(-180)", -math.pi), ("!radians -2*pi/3 + 1", 1 - 2 * math.pi / 3)])
def test_angles_read_as_rosparam_reads_them(text, expected):
    from worldgen.launch.params_xml import load_yaml

    assert load_yaml(f"a: {text}")["a"] == pytest.approx(expected)


@pytest.mark.parametrize("text, message", [
    ('a: !radians __import__("os")', "is not an angle"),
    ("d: " + "[" * 3000 + "]" * 3000, "nests more than 64 levels"),
    ("a: &a [1,1,1,1,1,1,1,1,1,1]\n" + "".join(f"{b}: &{b} [{', '.join(['*' + a] * 10)}]\n"
                                             for a, b in zip("abcde", "bcdef")), "more than 200,000 values"),
])
def test_a_hostile_rosparam_document_is_refused_quickly(text, message):
    from worldgen.launch.params_xml import load_yaml

    with pytest.raises(ParamError, match=message):
        load_yaml(text)


def test_what_the_master_cannot_hold_is_said():
    import datetime

    from worldgen.launch.params_xml import storable

    assert "not a string" in storable({1: 0.5})
    assert "date" in storable({"when": datetime.date(2001, 1, 1)})
    assert storable({"ok": [1, 2.5, "x", True, {"deep": -3}]}) is None


LAUNCH = """<launch>
  <arg name="distance" default="0.8"/>
  <param name="lab" value="2"/>
  <param name="ratio" value="0.25"/>
  <param name="name" value="intro robo"/>
  <param name="forced" type="str" value="12"/>
  <param name="notes" textfile="$(dirname)/notes.txt"/>
  <rosparam file="$(dirname)/speeds.yaml" command="load"/>
  <rosparam ns="limits">{linear: 0.22, angular: 2.84}</rosparam>
  <rosparam param="angle">!degrees 180</rosparam>
  <rosparam subst_value="true">target: $(arg distance)</rosparam>
  <remap from="scan" to="/base_scan"/>
  <group ns="robot1">
    <param name="inner" value="true"/>
    <env name="ROBOT" value="one"/>
    <node pkg="roslaunch" type="roslaunch-check" name="driver" args="--flag 'two words'">
      <param name="~kp" value="$(arg distance)"/>
      <param name="gain" type="double" value="2"/>
      <rosparam>{weights: [1, 2, 3], nested: {deep: yes}}</rosparam>
      <remap from="cmd_vel" to="cmd_vel_mux"/>
    </node>
  </group>
  <include file="$(dirname)/inner.launch" ns="robot2"/>
  <rosparam command="delete" param="ratio"/>
</launch>
"""
INNER = """<launch>
  <param name="from_inner" value="-3"/>
  <node pkg="roslaunch" type="roslaunch-check" name="helper" required="true"/>
  <node pkg="roslaunch" type="roslaunch-check" name="again" respawn="true"/>
</launch>
"""


@pytest.fixture
def launch(tmp_path) -> Path:
    (tmp_path / "notes.txt").write_text("line one\nline two\n")
    (tmp_path / "speeds.yaml").write_text("speeds:\n  cruise: 0.12\n  slow: !!float 3\n")
    (tmp_path / "inner.launch").write_text(INNER)
    path = tmp_path / "main.launch"
    path.write_text(LAUNCH)
    return path


def flat(params: dict) -> dict:
    """``params`` as leaves (roslaunch's own loader lists a mapping's entries one by one)."""
    out = {}
    for name, value in params.items():
        if isinstance(value, dict):
            out.update(flat({f"{name}/{k}": v for k, v in value.items()}))
        else:
            out[name] = value
    return out


def test_a_launch_files_parameters_remaps_and_env(launch):
    info = read_launch(launch, {"distance": "0.6"}, environ={})
    params = flat(info.params)
    assert params["/lab"] == 2 and params["/forced"] == "12" and params["/notes"] == "line one\nline two\n"
    assert params["/ratio"] == 0.25   # a delete runs before roslaunch sets anything: it does not undo the file's own
    assert params["/speeds/slow"] == 3.0 and params["/limits/angular"] == 2.84 and params["/target"] == 0.6
    assert params["/angle"] == pytest.approx(math.pi)
    assert params["/robot1/driver/kp"] == 0.6 and params["/robot1/driver/gain"] == 2.0
    assert params["/robot1/driver/weights"] == [1, 2, 3] and params["/robot1/driver/nested/deep"] is True
    assert params["/robot1/inner"] is True and params["/robot2/from_inner"] == -3
    driver, helper, again = info.nodes
    assert driver.remaps == (("scan", "/base_scan"), ("cmd_vel", "cmd_vel_mux")) and driver.env == (("ROBOT", "one"),)
    assert helper.ns == "/robot2" and helper.remaps == (("scan", "/base_scan"),) and helper.env == ()
    assert (helper.required, helper.respawn, again.required, again.respawn, driver.required) == \
        (True, False, False, True, False)
    assert not info.findings, info.findings


def test_params_merge_and_file_text_is_substituted_as_roslaunch_does(tmp_path):
    (tmp_path / "gains.yaml").write_text("gain: $(arg g)\n")
    path = tmp_path / "merge.launch"
    path.write_text('<launch>\n  <arg name="g" default="0.7"/>\n  <param name="pid/kp" value="0.8"/>\n'
                    '  <rosparam>pid: {ki: 0.1}</rosparam>\n'
                    '  <rosparam file="$(dirname)/gains.yaml" subst_value="true"/>\n</launch>\n')
    assert read_launch(path, environ={}).params == {"/pid/kp": 0.8, "/pid/ki": 0.1, "/gain": 0.7}


def test_roslaunchs_own_loader_finds_the_same_parameters(launch, tmp_path):
    need_module("roslaunch")
    (theirs,) = roslaunch_load([(launch, ["distance:=0.6"])], ros_env(tmp_path))
    ours = read_launch(launch, {"distance": "0.6"}, environ={})
    expected = {k: v for k, v in theirs["params"].items() if k not in ("/rosdistro", "/rosversion")}
    got = {k: (v if isinstance(v, (str, int, float, bool)) else str(v)) for k, v in flat(ours.params).items()}
    assert got == expected
    assert [(n["namespace"].rstrip("/") + "/" + n["name"]) for n in theirs["nodes"]] == \
        [n.full_name for n in ours.nodes]


@pytest.mark.parametrize("element, message", [
    ('<param name="~x" value="1"/>', "private parameter '~x' outside a <node>"),
    ('<param name="x" type="int" value="one"/>', "param /x: 'one' is not an int"),
    ("<rosparam>[1, 2]</rosparam>", "must hold a YAML mapping"),
    ("<rosparam>a: [1, 2</rosparam>", "not YAML"),
    ('<rosparam param="big">4294967296</rosparam>', "does not fit a 32-bit integer"),
    ('<param name="p" textfile="/no/such/file"/>', "/no/such/file"),
    ('<remap from="a"/>', "needs both from= and to="),
    ('<node pkg="p" type="t" name="n" required="true" respawn="true"/>', "both required and respawn"),
])
def test_what_roslaunch_would_refuse_is_a_finding_with_its_line(tmp_path, element, message):
    path = tmp_path / "bad.launch"
    path.write_text(f"<launch>\n  {element}\n</launch>\n")
    findings = read_launch(path, environ={}).findings
    assert [f.where for f in findings] == [f"{path}:2"] and message in findings[0].message, findings
