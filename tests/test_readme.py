"""The README's promises hold: its spec examples load and build, and its opening commands name real things."""

from __future__ import annotations

import re

import pytest
from conftest import CliRunner

from conftest import REPO
from worldgen.cli import main

README = (REPO / "README.md").read_text(encoding="utf-8")
YAML_BLOCKS = re.findall(r"```yaml\n(.*?)```", README, flags=re.S)


def test_readme_has_spec_examples():
    assert len(YAML_BLOCKS) >= 2


@pytest.mark.parametrize("index", range(len(YAML_BLOCKS)))
def test_readme_spec_example_builds(tmp_path, index):
    spec = tmp_path / "example.yaml"
    spec.write_text(YAML_BLOCKS[index])
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    (world,) = (tmp_path / "out").glob("*.world")
    assert "<static>1</static>" in world.read_text()


def test_readme_opens_with_the_two_commands():
    first_block = re.search(r"```sh\n(.*?)```", README, flags=re.S).group(1).splitlines()
    assert first_block[0].startswith("python3 -m pip install . && worldgen build examples/")
    example = re.search(r"worldgen build (examples/\S+)", first_block[0]).group(1)
    assert (REPO / example).is_file()
    assert first_block[1].startswith("bash .ci/run")
