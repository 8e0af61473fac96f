"""Shared test fixtures: where the repository, its examples and the shared corpus are."""

from __future__ import annotations

from pathlib import Path

import pytest

from browserpage import chromium  # noqa: F401  (one headless browser for every test module)

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SHARED = REPO.parent / "shared"
CORPUS = SHARED / "corpus"


@pytest.fixture(scope="session")
def corpus() -> Path:
    """``../shared/corpus`` (real worlds saved with Gazebo); tests using it skip when it is absent."""
    if not CORPUS.is_dir():
        pytest.skip(f"the shared corpus is not beside this checkout ({CORPUS} is missing)")
    return CORPUS


def CliRunner():   # noqa: N802  (stands in for click.testing.CliRunner in every test)
    """click's test runner with stderr apart from stdout, and ``output`` holding both, as click 8.2+ gives
    them; click 8.1 (the last for Python 3.8) mixes them unless asked, and then ``output`` is stdout alone."""
    import inspect

    from click.testing import CliRunner as Runner

    if "mix_stderr" not in inspect.signature(Runner.__init__).parameters:
        return Runner()

    class _Result:
        def __init__(self, result):
            self._result = result

        def __getattr__(self, name):
            return getattr(self._result, name)

        @property
        def output(self) -> str:
            return self._result.stdout + self._result.stderr

    class _Runner(Runner):
        def __init__(self, **kwargs):
            super().__init__(mix_stderr=False, **kwargs)

        def invoke(self, *args, **kwargs):
            return _Result(super().invoke(*args, **kwargs))

    return _Runner()
