"""An output's suffix says what its bytes are: ``view -o x.png`` (a page) and ``preview -o x.jpg`` (PNG bytes)
are refused in one line naming the name to use, before any work and with nothing written."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import CliRunner

from worldgen.cli import main

ROOM = str(Path(__file__).resolve().parent.parent / "examples" / "enclosed_room.yaml")


@pytest.mark.parametrize("argv, name, wanted", [
    (["view", ROOM, "-o", "room.png"], "room.png", "room.html"),
    (["preview", ROOM, "-o", "room.jpg"], "room.jpg", "room.png"),
    (["preview", ROOM, "-o", "room"], "room", "room.png"),
    (["new", "room", "-o", "room.json"], "room.json", "room.yaml"),
    (["drive", ROOM, "--plot", "curve.svg"], "curve.svg", "curve.png"),
    (["drive", ROOM, "--html", "run.png"], "run.png", "run.html"),
    (["run", ROOM, "node.py", "--plot", "run.pdf"], "run.pdf", "run.png"),
    (["validate", ROOM, "--junit", "report.json"], "report.json", "report.xml"),
    (["run", ROOM, "node.py", "--junit", "report.json"], "report.json", "report.xml"),
])
def test_a_wrong_suffix_is_refused_in_one_line(tmp_path, monkeypatch, argv, name, wanted):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "node.py").write_text("print('hi')\n")
    result = CliRunner().invoke(main, argv)
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"worldgen: error: {name}: ") and f"name it {wanted}" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["node.py"]   # nothing written


def test_the_right_suffix_writes_what_it_says(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name in ("room.png", "ROOM.PNG"):
        result = CliRunner().invoke(main, ["preview", ROOM, "-o", name])
        assert result.exit_code == 0, result.output
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    result = CliRunner().invoke(main, ["new", "lab", "-o", "lab.yml"])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("name", ["flat.world", "flat.sdf", "flat.launch"])
def test_build_refuses_an_output_folder_named_like_a_file(tmp_path, monkeypatch, name):
    """build's -o is the folder NAME.world goes into: -o flat.world would make a folder flat.world/ holding
    flat.world/enclosed_room.world; refused in one line, nothing written (an existing folder of that name is
    still a folder, and used)."""
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["build", ROOM, "-o", name])
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"worldgen: error: {name}: -o is the folder") and "give a folder: -o . writes" in line
    assert list(tmp_path.iterdir()) == []
    (tmp_path / name).mkdir()
    result = CliRunner().invoke(main, ["build", ROOM, "-o", name])
    assert result.exit_code == 0 and (tmp_path / name / "enclosed_room.world").is_file(), result.output
