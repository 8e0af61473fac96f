"""The class runtime, without ROS: what a node imports is read from its source (never run), looked up for the
Python that runs it in one child process, and every gap is a finding that names the module, the file and line and
the package; the table's Debian names exist; `.ci/run`, the README and the code name one class runtime; and
`worldgen doctor` prints one table and one apt line.

The "nodes' Python" here is this test's own interpreter (``WORLDGEN_ROS_PYTHON``), so these tests need no rospy;
tests/test_bridge_runtime.py runs real rospy nodes.
"""

from __future__ import annotations

import importlib.util
import json
import re
import shutil
import subprocess
import sys
import textwrap

import pytest

from conftest import REPO, CliRunner
from worldgen.cli import main
from worldgen.runtime.imports import read_source
from worldgen.runtime.naming import Naming
from worldgen.runtime.table import CLASS_RUNTIME, TABLE, install_hint, provider, runtime_modules
from worldgen.runtime.check import findings, survey

ABSENT_CANDIDATES = ("sklearn", "pandas", "serial", "pygame", "sympy")   # in the table, not in the class runtime


def absent_module(python_has=lambda m: importlib.util.find_spec(m) is not None) -> str:
    """A module of the table that this Python does not have (the test skips when it has them all)."""
    for module in ABSENT_CANDIDATES:
        if not python_has(module):
            return module
    pytest.skip(f"this Python has every one of {ABSENT_CANDIDATES}")


def imports(text: str):
    return read_source(textwrap.dedent(text)).imports


# ---- the import reader ---------------------------------------------------------------------------------------

def test_plain_imports_give_the_module_its_top_level_name_and_line():
    found = imports("""\
        import rospy, numpy as np
        from tf.transformations import euler_from_quaternion
        import sensor_msgs.msg
        """)
    assert [(i.module, i.top, i.line, i.optional) for i in found] == [
        ("rospy", "rospy", 1, False), ("numpy", "numpy", 1, False),
        ("tf.transformations", "tf", 2, False), ("sensor_msgs.msg", "sensor_msgs", 3, False)]


@pytest.mark.parametrize("handler", ["except ImportError:", "except ModuleNotFoundError:", "except Exception:",
                                     "except:", "except (ValueError, ImportError) as err:",
                                     "except BaseException:"])
def test_guarded_imports_are_optional(handler):
    found = imports(f"""\
        try:
            import numpy
            if True:
                from scipy import signal
        {handler}
            numpy = None
        import rospy
        """)
    assert {i.top: i.optional for i in found} == {"numpy": True, "scipy": True, "rospy": False}


def test_a_fallback_in_the_handler_is_optional_but_other_handlers_and_else_are_not():
    found = imports("""\
        try:
            import cPickle as pickle
        except ImportError:
            import pickle
        try:
            import numpy
        except KeyboardInterrupt:
            import sys
        else:
            import yaml
        """)
    assert {i.top: i.optional for i in found} == {"cPickle": True, "pickle": True, "numpy": False, "sys": False,
                                                  "yaml": False}


@pytest.mark.parametrize("gives_up", ["raise", "sys.exit('install numpy')", "exit(1)",
                                      "raise SystemExit('no numpy')", "rospy.signal_shutdown('no numpy')"])
def test_a_handler_that_gives_up_does_not_make_the_import_optional(gives_up):
    found = imports(f"""\
        try:
            import numpy
        except ImportError:
            print("numpy is needed")
            {gives_up}
        """)
    assert [(i.top, i.optional) for i in found] == [("numpy", False)]


def test_imports_inside_functions_count_and_name_the_function():
    found = imports("""\
        import rospy

        class Stopper(object):
            import math

            def on_scan(self, msg):
                import numpy as np
                return np.array(msg.ranges)

        def main():
            from tf.transformations import euler_from_quaternion
        """)
    assert [(i.top, i.line, i.optional, i.function) for i in found] == [
        ("rospy", 1, False, ""), ("math", 4, False, ""), ("numpy", 7, False, "Stopper.on_scan"),
        ("tf", 11, False, "main")]


def test_version_branches_are_optional():
    found = imports("""\
        import sys
        if sys.version_info[0] < 3:
            import Tkinter as tk
        else:
            import tkinter as tk
        if sys.version_info.major == 2:
            import urllib2
        if sys.version.startswith("2"):
            import ConfigParser
        if args.version:
            import yaml
        """)
    assert {i.top: i.optional for i in found} == {"sys": False, "Tkinter": True, "tkinter": True, "urllib2": True,
                                                  "ConfigParser": True, "yaml": False}


def test_future_and_relative_imports_are_skipped():
    found = imports("""\
        from __future__ import print_function
        from . import helpers
        from .utils import clamp
        from ..pkg import thing
        import helpers2
        """)
    assert [i.module for i in found] == ["helpers2"]


def test_needed_keeps_the_first_required_import_of_each_module():
    node = read_source("try:\n    import numpy\nexcept ImportError:\n    pass\nimport rospy\nimport numpy as np\n"
                       "import rospy.timer\n")
    assert {m: i.line for m, i in node.needed().items()} == {"rospy": 5, "numpy": 6}


def test_a_python_2_node_is_a_finding_with_its_line_not_a_crash(tmp_path):
    node = tmp_path / "py2_node.py"
    node.write_text('#!/usr/bin/env python\nimport math\n\nprint "starting"\n')
    [report] = survey([node], sys.executable).reports
    assert report.source.error[0] == 4 and report.found == {"math": "stdlib"}
    [finding] = findings([report], sys.executable)
    assert (finding.check, finding.severity, finding.where) == ("runtime", "error", f"{node}:4")
    assert "does not parse as Python 3" in finding.message and "print" in finding.message
    assert read_source(b"import os\x00\n").error[0] == 1   # null bytes: a finding too


def test_a_file_that_does_not_parse_still_has_its_imports_read_line_by_line():
    node = read_source(textwrap.dedent("""\
        import rospy, numpy as np
        from sklearn.linear_model import LinearRegression
        from __future__ import division
        try:
            import cPickle as pickle
        except ImportError:
            import pickle
        print "ready"
        """))
    assert node.error[0] == 8
    assert [(i.module, i.line, i.optional) for i in node.imports] == [
        ("rospy", 1, False), ("numpy", 1, False), ("sklearn.linear_model", 2, False), ("cPickle", 5, True),
        ("pickle", 7, True)]


# ---- the table ------------------------------------------------------------------------------------------------

def test_the_tables_rows_the_class_relies_on():
    assert (provider("numpy").debian, provider("numpy").noetic) == ("python3-numpy", "python3-numpy")
    assert (provider("tf").debian, provider("tf").noetic) == ("python3-tf", "ros-noetic-tf")
    assert (provider("tf2_ros").debian, provider("tf2_ros").noetic) == ("python3-tf2-ros", "ros-noetic-tf2-ros")
    assert (provider("cv2").debian, provider("cv_bridge").noetic) == ("python3-opencv", "ros-noetic-cv-bridge")
    assert provider("tkinter").debian == "python3-tk" and provider("PIL").debian == "python3-pil"
    assert provider("gazebo_msgs").worldgen and provider("gazebo_msgs").debian is None
    assert provider("turtlebot3_msgs").debian is None and "catkin workspace" in provider("turtlebot3_msgs").note
    rule = provider("ackermann_msgs")
    assert (rule.debian, rule.noetic, rule.guessed) == ("python3-ackermann-msgs", "ros-noetic-ackermann-msgs", True)
    assert provider("not_a_known_module") is None and provider("Tkinter").python3 == "tkinter"


def test_install_hints_name_both_systems():
    assert install_hint("tf") == "apt install python3-tf (ROS Noetic: ros-noetic-tf)"
    assert install_hint("tf", noetic=True) == "apt install ros-noetic-tf (Debian: python3-tf)"
    assert install_hint("numpy") == "apt install python3-numpy"
    assert "ros-noetic-turtlebot3-msgs" in install_hint("turtlebot3_msgs")
    assert "pip install" in install_hint("not_a_known_module")


@pytest.mark.parametrize("typed, meant", [("rospyy", "rospy"), ("sensor_msg", "sensor_msgs"),
                                          ("geometry_msg", "geometry_msgs"), ("nmupy", "numpy")])
def test_a_module_a_letter_or_two_off_a_known_one_is_named_as_a_typo(typed, meant):
    """A student's misspelt import gets the module meant, not an apt search for the misspelling (ROS 2 too)."""
    hint = install_hint(typed)
    assert hint.startswith(f"did you mean {meant}? fix the import") and f"if {typed} is what you meant" in hint
    assert Naming("jazzy").hint(typed).startswith(f"did you mean {meant}?")


def test_an_unknown_module_far_from_every_known_one_gets_the_search_only():
    assert install_hint("zebra_toolkit").startswith("worldgen does not know which package provides zebra_toolkit")
    assert Naming("humble").hint("rclpyy").startswith("did you mean rclpy?")


def test_the_class_runtime_is_sorted_and_each_package_provides_a_module_of_the_table():
    assert list(CLASS_RUNTIME) == sorted(set(CLASS_RUNTIME))
    provided = {p.debian for p in TABLE.values()}
    assert [p for p in CLASS_RUNTIME if p not in provided] == []
    for module in ("rospy", "numpy", "tf", "tf2_ros", "cv_bridge", "cv2", "tkinter", "scipy", "matplotlib",
                   "actionlib", "message_filters", "PIL", "yaml"):
        assert module in runtime_modules(), module
    assert not {"sklearn", "pandas"} & set(runtime_modules())


def test_every_debian_name_in_the_table_exists():
    """`apt-cache show` knows every Debian package the table names (the names were checked on Debian 12)."""
    if shutil.which("apt-cache") is None:
        pytest.skip("no apt-cache here (not a Debian or Ubuntu system)")
    names = sorted({p.debian for p in TABLE.values() if p.debian} | set(CLASS_RUNTIME))
    proc = subprocess.run(["apt-cache", "show", "--no-all-versions", *names], capture_output=True, text=True)
    known = set(re.findall(r"^Package: (\S+)$", proc.stdout, flags=re.M))
    if not known:
        pytest.skip("apt's package lists are empty here (run apt-get update)")
    assert sorted(set(names) - known) == []


def test_ci_the_readme_and_the_code_name_one_class_runtime():
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    block = re.search(r"^CLASS_RUNTIME=\((.*?)^\)", ci, flags=re.S | re.M).group(1)
    listed = [w for line in block.splitlines() for w in line.split("#", 1)[0].split()]
    assert listed == list(CLASS_RUNTIME)
    assert 'DEB_PACKAGES+=("${CLASS_RUNTIME[@]}")' in ci
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    [line] = [ln for ln in readme.splitlines() if "apt-get install" in ln and "python3-actionlib" in ln]
    words = line.split("apt-get install", 1)[1].split()
    assert [w for w in words if not w.startswith("-")] == list(CLASS_RUNTIME)


# ---- looking modules up for the nodes' Python -------------------------------------------------------------------

def test_gaps_are_findings_naming_module_file_line_and_package(tmp_path):
    missing = absent_module()
    folder = tmp_path / "ana"
    folder.mkdir()
    (folder / "helpers.py").write_text("def clamp(x):\n    return x\n")
    node = folder / "stop_at_wall.py"
    node.write_text(f"#!/usr/bin/env python3\nimport math\nimport json\nimport helpers\nimport {missing}\n"
                    "import worldgen_no_such_module_here\nfrom gazebo_msgs.srv import GetModelState\n"
                    "def later():\n    import Tkinter\n")
    [report] = survey([node], sys.executable).reports
    assert report.found["math"] == "stdlib" and report.found["helpers"] == "local"
    assert report.found["gazebo_msgs"] in ("worldgen", "site")   # worldgen makes it for the nodes it runs
    assert report.gaps() == [missing, "worldgen_no_such_module_here", "Tkinter"]
    by_where = {f.where: f for f in findings([report], sys.executable)}
    package = provider(missing).debian
    gap = by_where[f"{node}:5"]
    assert (gap.check, gap.severity) == ("runtime", "error")
    assert gap.message == f"{missing} ({package}) is not installed for {sys.executable}: stop_at_wall.py:5 imports it"
    assert gap.fix == f"apt install {package}"
    unknown = by_where[f"{node}:6"]
    assert "worldgen_no_such_module_here is not installed" in unknown.message and "pip install" in unknown.fix
    old = by_where[f"{node}:9"]
    assert "Tkinter does not exist in Python 3" in old.message and "(in later, when that runs)" in old.message
    assert "tkinter" in old.fix


def test_the_workspaces_own_unbuilt_python_is_a_build_finding(tmp_path):
    """A package's own Python (src/ with setup.py) and its own messages are not apt's: build the workspace."""
    package = tmp_path / "ws" / "src" / "lab_bot"
    (package / "scripts").mkdir(parents=True)
    (package / "src" / "lab_bot").mkdir(parents=True)
    (package / "src" / "lab_bot" / "__init__.py").write_text("")
    (package / "setup.py").write_text("from setuptools import setup\n")
    (package / "package.xml").write_text("<package format='2'><name>lab_bot</name></package>")
    sibling = tmp_path / "ws" / "src" / "lab_interfaces"
    sibling.mkdir()
    (sibling / "package.xml").write_text("<package format='2'><name>lab_interfaces</name></package>")
    node = package / "scripts" / "drive.py"
    node.write_text("import lab_bot.control\nfrom lab_interfaces.msg import Goal\n")
    [report] = survey([node], sys.executable).reports
    assert report.found == {"lab_bot": "build", "lab_interfaces": "build"}
    for finding in findings([report], sys.executable):
        assert "catkin workspace's own Python" in finding.message and "catkin_make" in finding.fix


def test_one_child_process_answers_for_forty_submissions(tmp_path, monkeypatch):
    import worldgen.runtime.check as runtime_check

    calls = []
    real_run = subprocess.run
    monkeypatch.setattr(runtime_check.subprocess, "run", lambda *a, **k: calls.append(a) or real_run(*a, **k))
    nodes = []
    for i in range(40):
        scripts = tmp_path / f"s{i:02d}" / "scripts"
        scripts.mkdir(parents=True)
        (scripts / "utils.py").write_text("")
        nodes.append(scripts / "stop_at_wall.py")
        nodes[-1].write_text("import math\nimport numpy\nimport yaml\nimport utils\nimport worldgen_absent_xyz\n")
    reports = survey(nodes, sys.executable).reports
    assert len(calls) == 1 and len(reports) == 40
    assert all(r.found["utils"] == "local" and r.gaps() == ["worldgen_absent_xyz"] for r in reports)


# ---- worldgen doctor --------------------------------------------------------------------------------------------

@pytest.fixture
def three_submissions(tmp_path, monkeypatch):
    """ana's node is fine, bo's imports a module this Python lacks (twice), cy's is Python 2."""
    monkeypatch.setenv("WORLDGEN_ROS_PYTHON", sys.executable)
    missing = absent_module()
    subs = tmp_path / "submissions"
    for name, text in (("ana", "import math\nimport numpy as np\n"),
                       ("bo", f"import numpy\nimport {missing}\ndef fit():\n    from {missing} import x\n"),
                       ("cy", 'import numpy\nprint "hello"\n')):
        (subs / name / "scripts").mkdir(parents=True)
        (subs / name / "package.xml").write_text(f"<package format='2'><name>{name}</name></package>")
        (subs / name / "scripts" / "stop_at_wall.py").write_text(text)
    monkeypatch.chdir(tmp_path)
    return missing


def test_doctor_prints_the_table_and_one_apt_line(three_submissions):
    missing = three_submissions
    result = CliRunner().invoke(main, ["doctor", "submissions"])
    assert result.exit_code == 1, result.output
    lines = result.stdout.splitlines()
    assert lines[0].startswith(f"worldgen doctor: 3 node file(s), for {sys.executable} (Python ")
    assert lines[1].split() == ["module", "needed", "by", "provided", "by", "(Debian", "/", "ROS", "Noetic)", "state"]
    rows = {ln.split()[0]: ln for ln in lines[2:4]}
    assert list(rows) == sorted([missing, "numpy"], key=str.lower)
    assert rows["numpy"].split() == ["numpy", "submissions/ana/scripts/stop_at_wall.py:2", "and", "2", "more",
                                     "python3-numpy", "ok"]
    package = provider(missing).debian
    assert rows[missing].split() == [missing, "submissions/bo/scripts/stop_at_wall.py:2", package, "MISSING"]
    assert lines[4] == "not fixed by apt:"
    assert lines[5].startswith("  submissions/cy/scripts/stop_at_wall.py:2: stop_at_wall.py does not parse")
    assert [ln for ln in lines if "apt-get" in ln] == [lines[-1]] and lines[-1] == f"sudo apt-get install {package}"
    again = CliRunner().invoke(main, ["doctor", "submissions"])
    assert again.stdout == result.stdout   # deterministic


def test_doctor_json_and_exit_codes(three_submissions, tmp_path):
    missing = three_submissions
    result = CliRunner().invoke(main, ["doctor", "submissions", "--format", "json"])
    assert result.exit_code == 1
    doc = json.loads(result.stdout)
    assert doc["ok"] is False and doc["python"] == sys.executable and len(doc["nodes"]) == 3
    row = next(m for m in doc["modules"] if m["module"] == missing)
    assert row["state"] == "MISSING" and row["needed_by"] == [{"file": "submissions/bo/scripts/stop_at_wall.py",
                                                               "line": 2}]
    assert doc["install"] == f"sudo apt-get install {provider(missing).debian}"
    assert [f["where"] for f in doc["findings"]] == ["submissions/cy/scripts/stop_at_wall.py:2"]
    ok = CliRunner().invoke(main, ["doctor", "submissions/ana"])
    assert ok.exit_code == 0 and ok.stdout.splitlines()[-1] == "nothing to install: every module is found"
    bad = CliRunner().invoke(main, ["doctor", "submissions/ana", "no_such_folder"])
    assert bad.exit_code == 2 and bad.stderr.strip() == ("worldgen: error: no_such_folder: no such file or folder "
                                                         "(give node files or a folder of submissions)")
    empty = tmp_path / "empty"
    empty.mkdir()
    nothing = CliRunner().invoke(main, ["doctor", str(empty)])
    assert nothing.exit_code == 2 and "no Python node found" in nothing.stderr


def test_doctor_with_no_argument_checks_the_class_runtime(monkeypatch):
    monkeypatch.setenv("WORLDGEN_ROS_PYTHON", sys.executable)
    result = CliRunner().invoke(main, ["doctor", "--format", "json"])
    doc = json.loads(result.stdout)
    assert [m["module"] for m in doc["modules"]] == runtime_modules() and doc["nodes"] == []
    rospy = next(m for m in doc["modules"] if m["module"] == "rospy")
    assert doc["rospy"] is (rospy["state"] == "ok")
    text = CliRunner().invoke(main, ["doctor"]).stdout.splitlines()
    assert text[0].startswith(f"worldgen doctor: the class runtime, for {sys.executable} (Python ")
    assert text[0].endswith("rospy found" if doc["rospy"] else "rospy MISSING: no node can run")
    from worldgen.ros1.transport import noetic

    missing = sorted({m["noetic" if noetic() else "debian"] for m in doc["modules"] if m["state"] == "MISSING"})
    assert result.exit_code == (1 if missing else 0)
    assert doc["packages"] == missing and doc["install"] == (f"sudo apt-get install {' '.join(missing)}"
                                                             if missing else None)


def test_pictures_draw_quietly_beside_debians_matplotlib(tmp_path):
    """With the class runtime's python3-matplotlib beside pip's (a --system-site-packages venv), Debian's
    mpl_toolkits shadows pip's and matplotlib warns about its 3D projection on every import: worldgen's pictures
    print nothing but their own line."""
    out = subprocess.run([sys.executable, "-m", "worldgen", "preview", str(REPO / "examples" / "enclosed_room.yaml"),
                          "-o", str(tmp_path / "room.png")], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "Warning" not in out.stderr and (tmp_path / "room.png").stat().st_size > 10000, out.stderr


def test_doctor_takes_a_folders_nodes_not_its_tests(tmp_path):
    """A student's folder with its node and its pytest tests (tests/, conftest.py): the node's imports are looked
    up, not pytest's, which no node imports; a node named test_*.py beside it is a node still."""
    from worldgen.runtime.doctor import node_files

    (tmp_path / "stop_at_wall.py").write_text("import rospy\n")
    (tmp_path / "test_drive.py").write_text("import rospy\n")
    (tmp_path / "conftest.py").write_text("import pytest\n")
    for folder in ("tests", "test"):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "test_stop.py").write_text("import pytest\nimport stop_at_wall\n")
    assert [p.name for p in node_files([tmp_path])] == ["stop_at_wall.py", "test_drive.py"]
