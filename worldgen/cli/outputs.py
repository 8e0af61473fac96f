"""Output names checked against what a command writes, before any work: a page named ``x.png`` or PNG bytes named
``x.jpg`` open as garbage (or not at all) in whatever the suffix picks, so a suffix that does not say what the
bytes are is refused in one line that gives the name to use instead."""

from __future__ import annotations

from pathlib import Path

from ..core.errors import InputError

KINDS = {
    "png": ((".png",), "a PNG picture"),
    "html": ((".html", ".htm"), "an HTML page"),
    "yaml": ((".yaml", ".yml"), "a YAML floorplan spec"),
    "junit": ((".xml",), "a JUnit XML report"),
}


def check_suffix(path: Path | None, kind: str, option: str) -> None:
    """Raise InputError when ``path`` (given to ``option``) does not end in a suffix of ``kind``; None passes."""
    if path is None:
        return
    suffixes, what = KINDS[kind]
    suffix = path.suffix
    if suffix.lower() in suffixes:
        return
    named = f"its name ends in '{suffix}'" if suffix else "its name has no suffix"
    raise InputError(f"{option} writes {what}, and {named}", path=path,
                     hint=f"name it {path.with_suffix(suffixes[0]).name if path.stem else 'out' + suffixes[0]}")
