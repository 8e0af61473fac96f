"""The installed wheel carries the templates, the TurtleBot3 descriptions and the vendored three.js (gitignored,
fetched by the build hook), not only the checkout."""

from __future__ import annotations

import configparser
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from conftest import REPO


@pytest.fixture(scope="module")
def unpacked_wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    proc = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(REPO)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        pytest.fail(f"building the wheel failed:\n{proc.stderr[-2000:]}")
    wheel = next(out.glob("worldgen-*.whl"))
    site = out / "site"
    zipfile.ZipFile(wheel).extractall(site)
    return site


def _run_from_wheel(site: Path, code: str, cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(site))
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=cwd, env=env)


def test_wheel_holds_templates_and_robot_descriptions(unpacked_wheel):
    pkg = unpacked_wheel / "worldgen"
    assert list((pkg / "templates").rglob("*")), "templates/ is not in the wheel"
    xacros = sorted(p.name for p in (pkg / "robots" / "worldgen_turtlebot3" / "urdf").glob("*.xacro"))
    for model in ("burger", "waffle", "waffle_pi"):
        assert f"turtlebot3_{model}.urdf.xacro" in xacros


def test_course_and_robot_work_from_the_wheel(unpacked_wheel, tmp_path):
    code = (
        "import sys, worldgen\n"
        f"assert worldgen.__file__.startswith({str(unpacked_wheel)!r}), worldgen.__file__\n"
        "from worldgen.robots import robot_urdf\n"
        "assert '<robot' in robot_urdf('waffle_pi')\n"
        "from worldgen.cli import main\n"
        "sys.argv = ['worldgen', 'course', '--workspace', 'ws']\n"
        "main()\n"
    )
    proc = _run_from_wheel(unpacked_wheel, code, tmp_path)
    assert proc.returncode == 0, proc.stderr
    src = tmp_path / "ws" / "src"
    assert (next(src.rglob("stop_at_wall.py"))).stat().st_mode & 0o111
    assert next(src.rglob("turtlebot3_in_enclosed_room.launch")).is_file()
    assert next(src.rglob("*.world")).is_file()


def test_the_wheels_worldgen_command_validates_with_its_simulation(unpacked_wheel, tmp_path):
    """The console script the wheel declares, called as pip's script calls it, on the class room: the world
    built and checked with the simulator, from the wheel's own files."""
    [dist_info] = unpacked_wheel.glob("worldgen-*.dist-info")
    scripts = configparser.ConfigParser()
    scripts.read(dist_info / "entry_points.txt")
    module, _, function = scripts["console_scripts"]["worldgen"].partition(":")
    code = (
        "import sys, worldgen\n"
        f"assert worldgen.__file__.startswith({str(unpacked_wheel)!r}), worldgen.__file__\n"
        f"from {module} import {function} as script\n"
        f"sys.argv = ['worldgen', 'validate', {str(unpacked_wheel / 'worldgen' / 'examples' / 'enclosed_room.yaml')!r},"
        " '--format', 'json']\n"
        "sys.exit(script())\n"
    )
    proc = _run_from_wheel(unpacked_wheel, code, tmp_path)
    assert proc.returncode == 0, proc.stderr
    [result] = json.loads(proc.stdout)["results"]
    assert result["ok"] and "stop-at-wall" in result["checks"], result


def test_wheel_holds_three_js_and_its_license_not_the_build_hook(unpacked_wheel):
    three = unpacked_wheel / "worldgen" / "view" / "three"
    names = sorted(p.name for p in three.iterdir())
    assert names == sorted(["three.module.min.js", "OrbitControls.js", "GLTFLoader.js", "BufferGeometryUtils.js",
                            "LICENSE", "VERSION"]), names
    assert "MIT License" in (three / "LICENSE").read_text(encoding="utf-8")
    assert (three / "VERSION").read_text(encoding="utf-8").startswith("0.170.0\n")
    assert not (unpacked_wheel / "worldgen" / "view" / "build_hook.py").exists()


def test_three_js_modules_load_from_the_wheel(unpacked_wheel, tmp_path):
    code = (
        "import json, worldgen\n"
        f"assert worldgen.__file__.startswith({str(unpacked_wheel)!r}), worldgen.__file__\n"
        "from worldgen.view import vendor\n"
        "assert vendor.is_vendored()\n"
        "print(json.dumps({k: len(v) for k, v in vendor.modules().items()}))\n"
    )
    proc = _run_from_wheel(unpacked_wheel, code, tmp_path)
    assert proc.returncode == 0, proc.stderr
    sizes = json.loads(proc.stdout)
    assert sorted(sizes) == ["BufferGeometryUtils", "GLTFLoader", "LICENSE", "OrbitControls", "three"]
    assert sizes["three"] > 500_000 and all(n > 0 for n in sizes.values())
