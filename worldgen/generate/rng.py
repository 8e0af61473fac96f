"""The generators' random numbers: one seeded stream per world, the same on every machine and every Python.

Only ``random.Random(seed).random()`` is used: the Mersenne Twister seeded from an integer and its 53-bit floats
are specified and unchanged from Python 3.2 to 3.13. The helpers built on it (integers below n, choices,
shuffles) are written here with plain arithmetic, because ``randrange``, ``choice``, ``shuffle`` and ``sample``
have changed how they draw between versions (3.12 reworked ``randrange``; ``sample`` and ``shuffle`` lost and
gained arguments), and a changed draw would change every world after it.
"""

from __future__ import annotations

import math
import random
from typing import List, Sequence, TypeVar

T = TypeVar("T")

MAX_SEED = 2 ** 32 - 1


class Rng:
    """A seeded stream: :meth:`random` in [0, 1), and what the generators build on it."""

    def __init__(self, seed: int):
        self._random = random.Random(int(seed))

    def random(self) -> float:
        return self._random.random()

    def uniform(self, low: float, high: float) -> float:
        """A float in [low, high)."""
        return low + (high - low) * self.random()

    def below(self, n: int) -> int:
        """An integer in 0 … n−1 (n ≥ 1)."""
        return min(int(self.random() * n), n - 1)

    def between(self, low: int, high: int) -> int:
        """An integer in low … high, both included."""
        return low + self.below(high - low + 1)

    def chance(self, p: float) -> bool:
        """True with probability p."""
        return self.random() < p

    def choice(self, items: Sequence[T]) -> T:
        return items[self.below(len(items))]

    def shuffled(self, items: Sequence[T]) -> List[T]:
        """A new list of ``items`` in random order (Fisher–Yates)."""
        out = list(items)
        for i in range(len(out) - 1, 0, -1):
            j = self.below(i + 1)
            out[i], out[j] = out[j], out[i]
        return out

    def step(self, low: float, high: float, grain: float) -> float:
        """A multiple of ``grain`` in [low, high] (``low`` itself when none is)."""
        first, last = math.ceil(low / grain - 1e-9), math.floor(high / grain + 1e-9)
        if last < first:
            return low
        return round(self.between(first, last) * grain, 6)
