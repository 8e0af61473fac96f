"""XML from users, parsed safely: no entity expansion, no DTD, no network, no huge trees; comments and processing
instructions dropped. Every reader of worlds, launch files, manifests and model.config files parses through here."""

from __future__ import annotations

import re
from pathlib import Path

from lxml import etree

from .errors import WorldFileError, WorldgenError
from .inputs import read_capped

_POSITION_SUFFIX = re.compile(r",?\s*line \d+, column \d+\s*$")


def parser() -> etree.XMLParser:
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, remove_comments=True,
                           remove_pis=True, huge_tree=False)


def parse_file(path: str | Path):
    """The root element of the XML file ``path``, or None when it cannot be read or parsed (for files that are
    looked at in passing, such as package.xml and model.config)."""
    try:
        return etree.fromstring(read_capped(path), parser())
    except (OSError, WorldgenError, etree.XMLSyntaxError, ValueError):
        return None


def parse_bytes(data: bytes, path: str | Path | None, *, what: str | None = None,
                hint: str = "fix the tag or attribute there", empty_hint: str | None = None):
    """The root element of ``data``; :class:`WorldFileError` naming ``path`` and the line when it is not
    well-formed. A byte-order mark and leading blank lines (or a licence comment's) are allowed; line numbers
    count them. ``what`` ("launch file" …) words the message."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    stripped = data.lstrip()
    skipped_lines = data[: len(data) - len(stripped)].count(b"\n")
    if not stripped:
        raise WorldFileError(f"the {what or 'file'} is empty", path=path, line=1, hint=empty_hint or hint)
    try:
        return etree.fromstring(stripped, parser())
    except etree.XMLSyntaxError as err:
        line = (err.lineno or 1) + skipped_lines
        message = _POSITION_SUFFIX.sub("", err.msg or str(err))
        prefix = f"the {what} is not" if what else "not"
        raise WorldFileError(f"{prefix} well-formed XML: {message}", path=path, line=line, hint=hint) from None
