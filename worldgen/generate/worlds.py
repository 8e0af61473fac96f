"""Making worlds: a kind, a seed, a count and options become spec texts, one per world.

World ``k`` of a batch (k from 0) is made from seed ``seed + k`` alone, with its own random stream
(:class:`~worldgen.generate.rng.Rng`), and is named ``KIND_SEED``; its header holds the command that makes exactly
it (``--seed seed + k``, every option written out). So a batch is the same as its worlds made one by one, and a
world of a class's set can be made again, or changed, on its own.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import import_module
from typing import Dict, List

from ..spec.model import Spec
from .options import KINDS, check_batch, command_line, make_options
from .rng import Rng
from .robot import RobotSpace, robot_space
from .text import spec_text


@dataclass(frozen=True)
class World:
    """One generated world: its name (``KIND_SEED``, also its file's stem), seed, spec and spec text; ``note``
    says what it lacks of what was asked (a kind's ``shortfall``: fewer rooms than ``--rooms``), else empty."""

    name: str
    seed: int
    spec: Spec
    text: str
    command: str
    note: str = ""

    @property
    def file_name(self) -> str:
        return f"{self.name}.yaml"


def _kind_module(kind: str):
    return import_module(f"{__package__}.{kind}")


def resolved(kind: str, options, space: RobotSpace | None = None):
    """``options`` with every value left to the robot filled in (what the header writes)."""
    return _kind_module(kind).resolve(options, space or robot_space(options.robot))


def make_world(kind: str, seed: int, options, space: RobotSpace | None = None) -> World:
    """The world ``seed`` of ``kind`` (options already checked and resolved); ``space``: the robot's, when
    known (else measured from its description)."""
    module = _kind_module(kind)
    name = f"{kind}_{seed}"
    spec, summary = module.make(name, options, space or robot_space(options.robot), Rng(seed))
    command = command_line(kind, seed, options)
    header = [f"{name}: {summary}, for the {options.robot}.",
              "Made by this command, which makes the same file on every machine:",
              f"  {command}",
              f"Build it with: worldgen build {name}.yaml -o worlds/   (or check it: worldgen validate {name}.yaml)"]
    short = getattr(module, "shortfall", None)   # a kind that may give less than asked says so
    return World(name, seed, spec, spec_text(spec, header), command, (short and short(spec, options)) or "")


def generate(kind: str, seed: int, count: int = 1, values: Dict | None = None, space: RobotSpace | None = None
             ) -> List[World]:
    """``count`` worlds of ``kind`` from seeds ``seed`` … ``seed + count − 1``; ``values`` are the options by field
    name (None or missing: the default). InputError for a value out of its range. ``space`` stands in for the
    robot's measured one (the determinism tests run without the robot descriptions' dependencies)."""
    options = make_options(kind, dict(values or {}))
    check_batch(seed, count)
    space = space or robot_space(options.robot)
    options = resolved(kind, options, space)
    return [make_world(kind, s, options, space) for s in range(seed, seed + count)]


__all__ = ["KINDS", "World", "generate", "make_world", "resolved"]
