"""Findings: what a reader or a check has to say about a file, in a form a person and a CI system can read."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Literal

Severity = Literal["error", "warning", "info"]
SEVERITIES: tuple[Severity, ...] = ("error", "warning", "info")


@dataclass(frozen=True)
class Finding:
    """One statement about a file.

    ``check`` is a stable id (``enclosed``, ``spawn-clear``, ``sdf-parse`` …); ``where`` names the place (a file
    and line, a model/link, or world coordinates); ``fix`` says what to change.
    """

    check: str
    severity: Severity
    message: str
    where: str | None = None
    fix: str | None = None

    def to_dict(self) -> dict:
        return {k: v for k, v in asdict(self).items() if v is not None}
