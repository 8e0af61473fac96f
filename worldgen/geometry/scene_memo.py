"""What a scene's slices cost, computed once while the scene lives.

A world checked from several places asks for the same sections again for each: a world without a spawn is checked
from the deepest point of each of up to 8 rooms, and each check slices the scene at the same heights, unites the
same footprints and looks for the floor among the same slabs (a random 200 × 200 grid, 9 000 shapes: about 2 s a
room for the same union). :func:`remembered` keeps such a result with the scene it was computed from, for as long
as that scene object lives (a weak reference: nothing is kept for a scene that is gone, and nothing is added to the
scene itself, which is pickled to the simulator's process). A scene whose shape list changed (another shape
added, one replaced) is computed afresh.
"""

from __future__ import annotations

import threading
import weakref
from typing import Callable, Dict, Hashable, Tuple, TypeVar

T = TypeVar("T")

_MEMOS: Dict[int, Tuple[weakref.ref, dict]] = {}   # id(scene) -> (a weak reference to it, its results)
_LOCK = threading.RLock()   # validate -j N checks scenes from several threads; reentrant: a scene collected
                            # while the lock is held drops its results (_forget) under it


def _memo(scene) -> dict:
    """The results kept for ``scene`` (made empty the first time)."""
    key = id(scene)
    with _LOCK:
        entry = _MEMOS.get(key)
        if entry is not None and entry[0]() is scene:
            return entry[1]
        memo: dict = {}
        # the callback runs before the scene's memory (and so its id) can be reused; it drops only its own entry
        _MEMOS[key] = (weakref.ref(scene, lambda ref, key=key: _forget(key, ref)), memo)
        return memo


def _forget(key: int, ref: weakref.ref) -> None:
    """Drops the results kept under ``key`` if they are still those of the scene ``ref`` referred to."""
    with _LOCK:
        if key in _MEMOS and _MEMOS[key][0] is ref:
            del _MEMOS[key]


def remembered(scene, key: Hashable, make: Callable[[], T]) -> T:
    """``make()``, computed once per ``scene`` object, ``key`` and list of shapes (the same shape objects in the
    same order); the caller must not change what it gets (it is shared)."""
    memo = _memo(scene)
    full = (key, tuple(map(id, scene.shapes)))
    if full not in memo:
        memo[full] = make()
    return memo[full]
