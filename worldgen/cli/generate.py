"""``worldgen generate KIND --seed N [--count K] [--size WxH] [KIND's options] -o DIR``: seeded floorplan specs.

One subcommand per kind, its options made from :data:`worldgen.generate.options.FLAGS` (the same table the specs'
header lines are written from). Every spec of the batch is written, or none (all-or-nothing, as ``build``).
"""

from __future__ import annotations

from pathlib import Path

import click

from ..generate.options import FLAGS, KINDS, MAX_COUNT
from ..generate.rng import MAX_SEED
from . import SuggestingGroup

HELP = {
    "maze": "A maze on a grid of cells the robot can turn in: perfect or with loops, closed or with an entrance "
            "and an exit.",
    "rooms": "An apartment: rooms and a corridor joined by doors the robot fits through, furniture along the "
             "walls, windows in the outer walls.",
    "clutter": "One room with boxes and cylinders standing about, every gap between them closed or passable.",
    "arena": "One closed room with an outline that is not convex (right-angled or free), for wall following "
             "and stopping at a wall.",
    "track": "A closed loop of tape on the floor of a room, a smooth curve the Waffle Pi's camera can follow.",
}


def _click_option(flag) -> click.Option:
    """The click option of a :class:`~worldgen.generate.options.Flag` (default None: the kind's own default)."""
    names = [flag.flag]
    text = flag.help[0].upper() + flag.help[1:] + "."
    if flag.type == "bool":
        return click.Option(names, default=None, help=text)
    kinds = {"float": click.FLOAT, "int": click.INT, "text": click.STRING, "size": click.STRING,
             "choice": click.Choice(flag.choices) if flag.choices else click.STRING}
    meta = {"size": "WxH", "float": "M" if "(m" in flag.help else "X", "int": "N", "text": "NAME"}
    return click.Option(names, type=kinds[flag.type], default=None, metavar=meta.get(flag.type), help=text)


def _kind_command(kind: str) -> click.Command:
    from ..generate.options import OPTION_CLASSES

    defaults = OPTION_CLASSES[kind]()

    def callback(seed: int, count: int, output: Path, force: bool, **values) -> None:
        from ..core.fsio import write_files
        from ..generate.options import parse_size
        from ..generate.worlds import generate

        if values.get("size") is not None:
            values["size"] = parse_size(values["size"])
        worlds = generate(kind, seed, count, values)
        for path in write_files({output / w.file_name: w.text for w in worlds}, force=force):
            click.echo(f"wrote {path}")
        for world in worlds:
            if world.note:
                click.echo(f"worldgen: {world.file_name}: {world.note}", err=True)

    params = [
        click.Option(["--seed"], type=click.IntRange(0, MAX_SEED), required=True,
                     help="The first world's seed; world k of the batch is made from seed + k alone."),
        click.Option(["--count"], type=click.IntRange(1, MAX_COUNT), default=1, show_default=True,
                     help="How many worlds (KIND_SEED.yaml, one per seed)."),
        *[_click_option(f) for f in FLAGS[kind]],
        click.Option(["-o", "--output"], type=click.Path(file_okay=False, path_type=Path), default=Path("."),
                     show_default=True, help="The folder for the specs (made if missing)."),
        click.Option(["--force"], is_flag=True, help="Overwrite specs that exist."),
    ]
    shown = ", ".join(f"{f.flag.split('/')[0]} {_shown(getattr(defaults, f.field))}" for f in FLAGS[kind])
    return click.Command(kind, callback=callback, params=params,
                         help=f"{HELP[kind]}\n\nDefaults: {shown} (sized for the robot where empty).")


def _shown(value) -> str:
    if value is None:
        return "–"
    if isinstance(value, tuple):
        return "x".join(f"{v:g}" for v in value)
    if isinstance(value, bool):
        return "on" if value else "off"
    return f"{value:g}" if isinstance(value, float) else str(value)


@click.group("generate", cls=SuggestingGroup)
def generate_group() -> None:
    """Seeded worlds written as floorplan specs: KIND_SEED.yaml in the output folder, each closed, with a clear
    spawn and every room reachable through openings the robot fits, for the robot given (the Waffle Pi unless
    --robot says otherwise). The same command makes the same bytes on every machine; each spec's header holds
    the command that makes exactly it. Build them with worldgen build, check them with worldgen validate DIR,
    look at them all with worldgen preview DIR -o sheet.png."""


for _kind in KINDS:
    generate_group.add_command(_kind_command(_kind))

COMMANDS = [generate_group]
