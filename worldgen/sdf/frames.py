"""The frame graph of one scope (a model, or the world): every pose-bearing child and its ``relative_to``."""

from __future__ import annotations

from typing import Dict, List, Optional, Tuple

import numpy as np

from ..core import poses
from .context import ReadContext


class Frames:
    """The named frames of one scope (a model, or the world) and their poses in the scope's frame.

    Every pose-bearing child (link, nested model or include, joint, frame) is an entry, placed on first use and
    cached, so ``relative_to`` may name a sibling declared later. Names are looked up to their first entry (a
    duplicate name is reported elsewhere) but each entry keeps its own pose. Unknown names and cycles fall back to
    the scope frame with a warning.
    """

    def __init__(self, ctx: ReadContext, scope: str):
        self.ctx, self.scope = ctx, scope
        self.entries: List[Tuple[str, np.ndarray, Optional[str], str]] = []   # name, pose, relative_to, where
        self.first: Dict[str, int] = {}
        self.children: Dict[str, Frames] = {}
        self.placed: Dict[int, np.ndarray] = {}

    def add(self, name: str, pose: np.ndarray, relative_to: str | None, where: str) -> int:
        """Record an entry; returns its index for :meth:`place`."""
        self.entries.append((name, pose, relative_to, where))
        self.first.setdefault(name, len(self.entries) - 1)
        return len(self.entries) - 1

    def resolve(self, name: str, stack: tuple[str, ...] = ()) -> np.ndarray | None:
        """The pose of the frame called ``name`` (``a::b`` for one inside nested model ``a``), or None."""
        if name in ("__model__", "world", ""):
            return poses.IDENTITY
        if "::" in name:
            head, rest = name.split("::", 1)
            base, sub = self.resolve(head, stack), self.children.get(head)
            inner = sub.resolve(rest) if sub is not None else None
            return None if base is None or inner is None else base @ inner
        index = self.first.get(name)
        return None if index is None or name in stack else self.place(index, stack)

    def place(self, index: int, stack: tuple[str, ...] = ()) -> np.ndarray:
        """Entry ``index``'s pose in the scope frame, its ``relative_to`` resolved."""
        if index not in self.placed:
            name, pose, relative_to, where = self.entries[index]
            base = poses.IDENTITY
            if relative_to:
                found = self.resolve(relative_to, stack + (name,))
                if found is None:
                    why = "a cycle" if relative_to in stack + (name,) else "no frame of that name"
                    self.ctx.note("pose", "warning", f"'{name}' in {self.scope} has relative_to='{relative_to}', "
                                  f"{why} in that scope; treated as relative to its parent", where,
                                  "name a sibling link, model, joint or frame, or drop relative_to")
                else:
                    base = found
            self.placed[index] = base @ pose
        return self.placed[index]
