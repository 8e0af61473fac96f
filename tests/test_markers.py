"""The markers conftest.py gives (ros, browser, slow) name tests that exist, and are registered, so that a renamed
test does not silently fall into the fast loop or out of it."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import conftest

TESTS = Path(__file__).resolve().parent


def functions_of(module: str) -> set[str]:
    tree = ast.parse((TESTS / module).read_text(encoding="utf-8"))
    return {node.name for node in tree.body if isinstance(node, ast.FunctionDef) and node.name.startswith("test_")}


@pytest.mark.parametrize("table", ["ROS_TESTS", "SLOW_TESTS"])
def test_every_listed_test_exists(table):
    missing = {module: sorted(set(names) - functions_of(module))
               for module, names in getattr(conftest, table).items() if (TESTS / module).is_file()}
    assert {m: names for m, names in missing.items() if names} == {}


def test_every_marker_given_is_registered():
    text = (TESTS.parent / "pyproject.toml").read_text(encoding="utf-8")
    registered = set(re.findall(r'^\s*"(\w+): ', text.split("markers = [", 1)[1].split("]", 1)[0], re.MULTILINE))
    assert {"ros", "browser", "slow"} <= registered


def test_the_markers_follow_module_name_and_fixtures():
    assert conftest.markers_of("test_bridge_sim.py", "test_anything") == {"ros"}
    assert conftest.markers_of("test_bridge_rubrics.py", "test_anything") == set()
    assert conftest.markers_of("test_scaffold.py", "test_metapackage") == {"ros"}
    assert conftest.markers_of("test_view_index.py", "test_x", ("tmp_path", "chromium")) == {"browser"}
    assert conftest.markers_of("test_run_anything.py", "test_x", ("tag",)) == {"ros"}
    assert conftest.markers_of("test_validate.py", "test_our_examples_pass") == {"slow"}
