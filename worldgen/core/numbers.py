"""Numbers as worldgen writes and reads them: the short fixed decimal form of launch and package files, and the
whitespace-separated float lists of URDF and SDF attributes."""

from __future__ import annotations


def format_number(value: float) -> str:
    """A fixed, short decimal form for launch and package files: ``1.5``, ``-5.5``, ``0.0``, ``0.125``."""
    text = f"{float(value):.4f}".rstrip("0")
    text = text + "0" if text.endswith(".") else text
    return "0.0" if text in ("-0.0", "0.0") else text


def floats(text: str | None, n: int, default: float = 0.0) -> tuple[float, ...]:
    """The first ``n`` numbers of a URDF attribute (``"0 0.08 0.023"``), padded with ``default``; ValueError for
    a value that is not a number."""
    parts = (text or "").split()
    values = [float(p) for p in parts[:n]]
    return tuple(values + [default] * (n - len(values)))
