"""Numbers as worldgen writes and reads them: one formatter for every number worldgen writes (launch and package
files, SDF text, messages quoting a file's numbers), and the whitespace-separated float lists of URDF and SDF
attributes."""

from __future__ import annotations


def format_number(value: float, places: int | None = 4, *, point: bool = True) -> str:
    """A number as worldgen writes it: at most ``places`` decimals, trailing zeros trimmed, never ``-0``.

    With ``point``, a whole number keeps one decimal, as launch and package files have it (``1.5``, ``-5.5``,
    ``0.0``, ``0.125``); without, it has none, as SDF text has it (``format_number(x, 6, point=False)``: ``1.5``,
    ``2``, ``0``). ``places=None`` is Python's general form, six significant digits, exponents when needed
    (``1e+07``, ``0.001``): how a message quotes a file's own numbers, whatever their size."""
    if places is None:
        return f"{value:g}"
    text = f"{float(value):.{places}f}".rstrip("0")
    if text.endswith("."):
        text = text + "0" if point else text[:-1]
    if text in ("-0.0", "-0"):
        text = text[1:]
    return text


def format_numbers(values, places: int | None = 4, *, point: bool = True) -> str:
    """``values`` each as :func:`format_number` writes it, separated by spaces (SDF vectors, sizes, colours)."""
    return " ".join(format_number(v, places, point=point) for v in values)


def floats(text: str | None, n: int, default: float = 0.0) -> tuple[float, ...]:
    """The first ``n`` numbers of a URDF attribute (``"0 0.08 0.023"``), padded with ``default``; ValueError for
    a value that is not a number."""
    parts = (text or "").split()
    values = [float(p) for p in parts[:n]]
    return tuple(values + [default] * (n - len(values)))
