"""A contact sheet: every world and spec of a folder drawn side by side on one PNG, all to one scale, each with its
spawn and its name, so a teacher sees a whole generated set at once before handing it out.

The folder is searched as ``validate`` searches one (:func:`worldgen.check.discover.find_loose`: worlds, model
folders and specs, a world built from a spec beside it left out), in natural order (``maze_2`` before
``maze_10``). Each panel is :func:`worldgen.view.preview.draw_plan` of the world's picture, its axes as wide as
the widest world of the set, so a 4 m maze looks half as big as an 8 m one; the grid lines are a metre apart. The
PNG is deterministic, as ``preview``'s is.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Callable, List, Sequence

from ..core.errors import InputError, WorldgenError
from ..check.discover import find_loose
from ..core.mpl import matplotlib_agg

MAX_WORLDS = 400          # panels on one sheet
PANEL = 2.6               # inches per panel when the sheet is small …
MAX_WIDTH = 30.0          # … and the sheet at most this wide (inches): panels shrink to fit
DPI = 100
MARGIN = 0.4              # m round the widest world


def sheet_inputs(folder: str | Path) -> List[Path]:
    """The worlds and specs of ``folder`` to draw, in natural order; InputError when it holds none."""
    folder = Path(folder)
    found = [path for _, path in find_loose(folder)]
    if not found:
        raise InputError("holds no world or spec to draw", path=folder,
                         hint="give a folder of .yaml specs or .world files, e.g. one worldgen generate wrote")
    if len(found) > MAX_WORLDS:
        raise InputError(f"holds {len(found)} worlds and specs, more than the {MAX_WORLDS} one sheet draws",
                         path=folder, hint="split them into folders, or draw a few with worldgen preview FILE")
    return sorted(found, key=lambda p: _natural(str(p.relative_to(folder))))


def _natural(text: str) -> list:
    return [(0, int(part), "") if part.isdigit() else (1, 0, part) for part in re.split(r"(\d+)", text) if part]


def sheet(folder: str | Path, model_paths: Sequence[str | Path] = (), robot: str | None = None,
          failed: Callable[[Path, WorldgenError], None] | None = None) -> bytes:
    """The contact sheet of ``folder`` as PNG bytes (``robot``: the model whose spawn is drawn, else each
    world's own). A file that cannot be drawn (a student's broken spec) is a panel saying why, and is told to
    ``failed(path, error)``; with no ``failed``, or when no file can be drawn, its error is raised."""
    import dataclasses

    from .preview import picture

    folder = Path(folder)
    pictures: list = []   # (path, its Picture, or the error that kept it from being drawn)
    for path in sheet_inputs(folder):
        try:
            pic = picture(path, model_paths)
        except WorldgenError as err:
            if failed is None:
                raise
            pictures.append((path, err))
            continue
        if robot is not None and pic.spawn is not None:
            pic = dataclasses.replace(pic, spawn=dataclasses.replace(pic.spawn, model=robot))
        pictures.append((path, pic))
    errors = [(path, pic) for path, pic in pictures if isinstance(pic, WorldgenError)]
    if len(errors) == len(pictures):
        raise errors[0][1]
    for path, err in errors:
        failed(path, err)
    return render_sheet(pictures, str(folder))


def render_sheet(pictures, title: str) -> bytes:
    """Draw (path, :class:`~worldgen.view.preview.Picture`) pairs as one sheet: PNG bytes."""
    import io

    from .preview import _default_style

    matplotlib = matplotlib_agg()
    with matplotlib.rc_context(_default_style()):
        fig = _figure(pictures, title)
        out = io.BytesIO()
        fig.savefig(out, format="png", dpi=DPI, metadata={"Software": None})
    return out.getvalue()


def _figure(pictures, title: str):
    matplotlib_agg()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from .preview import _Bounds, _shown, draw_plan

    cols = math.ceil(math.sqrt(len(pictures)))
    rows = math.ceil(len(pictures) / cols)
    panel = min(PANEL, MAX_WIDTH / cols)
    head, foot = 0.6, 0.5   # inches for the title and for the key below
    width, height = cols * panel, rows * panel + head + foot
    fig = Figure(figsize=(width, height), dpi=DPI)
    FigureCanvasAgg(fig)
    drawn, shown = [], set()
    for k, (path, pic) in enumerate(pictures):
        r, c = divmod(k, cols)
        left, bottom = c * panel / width, 1 - (head + (r + 1) * panel) / height
        ax = fig.add_axes((left + 0.04 * panel / width, bottom + 0.02 * panel / height,
                           0.92 * panel / width, 0.84 * panel / height))
        if isinstance(pic, WorldgenError):
            _not_drawn(ax, path, pic)
            continue
        bounds, colours, marked = draw_plan(ax, pic)
        drawn.append((ax, bounds, pic, path))
        shown.update(colours)
        shown.update(m.type for m in pic.marks)
        shown.update(["marking"] if marked is not None else [])
        shown.update(["spawn"] if pic.spawn is not None else [])
    side = max(b.square(margin=MARGIN)[2] - b.square(margin=MARGIN)[0] for _, b, _, _ in drawn)
    for ax, bounds, pic, path in drawn:
        x0, y0, x1, y1 = bounds.square(margin=MARGIN) if bounds.box[0] != math.inf else _Bounds().square(MARGIN)
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        ax.set_xlim(cx - side / 2, cx + side / 2)
        ax.set_ylim(cy - side / 2, cy + side / 2)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xticks([float(v) for v in range(math.floor(cx - side / 2), math.ceil(cx + side / 2) + 1)])
        ax.set_yticks([float(v) for v in range(math.floor(cy - side / 2), math.ceil(cy + side / 2) + 1)])
        ax.tick_params(length=0, labelbottom=False, labelleft=False)
        ax.grid(True, color="#e6e6e6", linewidth=0.4, zorder=0)
        ax.set_axisbelow(True)
        for spine in ax.spines.values():
            spine.set_color("#cccccc")
        name = pic.title if pic.title and not pic.title.startswith("world 'default'") else path.stem
        ax.set_title(_shown(name), fontsize=8, pad=2)
    import textwrap

    missing = len(pictures) - len(drawn)
    heading = _shown(f"{title}: {len(pictures)} world{'s' if len(pictures) != 1 else ''}"
                     f"{f' ({missing} not drawn)' if missing else ''}, all to one scale ({side:.1f} m across each "
                     f"panel, grid 1 m)")
    fig.text(0.01, 1 - 0.08 / height, textwrap.fill(heading, max(30, int(width * 12))), fontsize=9, va="top")
    _key(fig, foot / height, shown)
    return fig


def _not_drawn(ax, path: Path, err: WorldgenError) -> None:
    """A panel for a file that could not be drawn: its name and why, in red."""
    import textwrap

    from .preview import _shown

    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        spine.set_color("#d62728")
    ax.set_title(_shown(path.stem), fontsize=8, pad=2)
    why = (f"line {err.line}: " if err.line else "") + err.message
    ax.text(0.5, 0.5, _shown("not drawn:\n" + textwrap.fill(why, 34)), ha="center", va="center",
            fontsize=7, color="#d62728", transform=ax.transAxes, wrap=True)


def _key(fig, height: float, shown: set) -> None:
    """A key of what the sheet shows, in one row at the bottom."""
    from matplotlib.patches import Patch

    from .preview import (DOOR_COLOUR, MARKING_GREY, OBSTACLE_COLOUR, ROBOT_COLOUR, WALL_COLOUR,
                          WINDOW_COLOUR)

    entries = ((WALL_COLOUR, WALL_COLOUR, "wall"), (OBSTACLE_COLOUR, OBSTACLE_COLOUR, "obstacle"),
               ("door", DOOR_COLOUR, "door"), ("window", WINDOW_COLOUR, "window"),
               ("marking", MARKING_GREY, "floor marking (in its colour)"),
               ("spawn", ROBOT_COLOUR, "spawn (arrow: heading)"))
    handles = [Patch(color=colour, alpha=0.5 if key == "spawn" else 1.0, label=label)
               for key, colour, label in entries if key in shown]
    if not handles:
        return
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(0.0, height / 2), ncol=len(handles),
               frameon=False, fontsize=8)
