"""Gazebo Classic's stock material scripts and the colour a camera sees of each, in one table.

A world names a stock material as ``<script><uri>file://media/materials/scripts/gazebo.material</uri>
<name>Gazebo/Wood</name></script>``. The numbers here are the ``diffuse`` colours of Gazebo Classic's
``media/materials/scripts/gazebo.material`` (the component the sun lights, so the one a camera mostly sees), with
the pass's alpha for the transparent ones (``Gazebo/RedTransparent`` is drawn half see-through). Textured materials
(wood, bricks, tiles, roads, grass) have no single colour: theirs is an estimate of the texture's average colour
under the pass's diffuse, good enough to draw them and to tell a camera's colour mask what the walls look like,
not to match a rendered pixel.

The spec reader offers these names for "did you mean" (:data:`worldgen.spec.model.GAZEBO_MATERIALS`); the world
reader colours a visual by them (:func:`script_color`); other script names (a world's own ``.material`` file) are
accepted as written and have no known colour.
"""

from __future__ import annotations

from typing import Dict, Optional, Tuple

RGBA = Tuple[float, float, float, float]

# name → (r, g, b, a), each 0–1; "textured" marks an estimated average (see the module docstring).
STOCK_COLORS: Dict[str, RGBA] = {
    # plain colours: gazebo.material's diffuse
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1, 1.0),
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/RedBright": (0.87, 0.26, 0.07, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/SkyBlue": (0.0, 0.0, 1.0, 1.0),          # its ambient is sky blue; the lit (diffuse) colour is blue
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/ZincYellow": (0.9725, 0.9529, 0.2078, 1.0),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
    "Gazebo/Indigo": (0.33, 0.0, 0.5, 1.0),
    "Gazebo/Gold": (0.8, 0.6487, 0.1208, 1.0),
    # transparent: the colour and the pass's alpha
    "Gazebo/GreyTransparent": (0.5, 0.5, 0.5, 0.5),
    "Gazebo/RedTransparent": (1.0, 0.0, 0.0, 0.5),
    "Gazebo/GreenTransparent": (0.0, 1.0, 0.0, 0.5),
    "Gazebo/BlueTransparent": (0.0, 0.0, 1.0, 0.5),
    "Gazebo/YellowTransparent": (1.0, 1.0, 0.0, 0.5),
    "Gazebo/OrangeTransparent": (1.0, 0.44, 0.0, 0.4),
    "Gazebo/DarkMagentaTransparent": (0.6, 0.0, 0.6, 0.5),
    # textured: an estimate of the texture's average colour
    "Gazebo/Wood": (0.62, 0.45, 0.28, 1.0),
    "Gazebo/WoodFloor": (0.55, 0.38, 0.22, 1.0),
    "Gazebo/WoodPallet": (0.6, 0.5, 0.36, 1.0),
    "Gazebo/Bricks": (0.58, 0.34, 0.26, 1.0),
    "Gazebo/CeilingTiled": (0.8, 0.8, 0.78, 1.0),
    "Gazebo/PaintedWall": (0.85, 0.83, 0.76, 1.0),
    "Gazebo/Residential": (0.3, 0.3, 0.3, 1.0),
    "Gazebo/Road": (0.3, 0.3, 0.3, 1.0),
    "Gazebo/Grass": (0.3, 0.45, 0.15, 1.0),
    "Gazebo/Gravel": (0.5, 0.48, 0.44, 1.0),
    "Gazebo/Rockwall": (0.45, 0.42, 0.38, 1.0),
    "Gazebo/RustySteel": (0.45, 0.3, 0.2, 1.0),
    "Gazebo/Chrome": (0.75, 0.75, 0.75, 1.0),
}

TEXTURED = frozenset(("Gazebo/Wood", "Gazebo/WoodFloor", "Gazebo/WoodPallet", "Gazebo/Bricks",
                      "Gazebo/CeilingTiled", "Gazebo/PaintedWall", "Gazebo/Residential", "Gazebo/Road",
                      "Gazebo/Grass", "Gazebo/Gravel", "Gazebo/Rockwall", "Gazebo/RustySteel", "Gazebo/Chrome"))

STOCK_NAMES: Tuple[str, ...] = tuple(STOCK_COLORS)


def script_color(name: Optional[str]) -> Optional[RGBA]:
    """The colour of a stock material script name (``Gazebo/Yellow``), None for any other name."""
    return STOCK_COLORS.get((name or "").strip())


def color_name(rgba: RGBA) -> str:
    """A colour as a person names it in a message: the stock material it is (``Gazebo/Yellow``), else its numbers
    (``rgb(0.9, 0.1, 0.1)``)."""
    for name, stock in STOCK_COLORS.items():
        if name not in TEXTURED and all(abs(a - b) < 1e-3 for a, b in zip(stock, rgba)):
            return name
    return "rgb(" + ", ".join(f"{round(c, 3):g}" for c in rgba[:3]) + ")"
