"""The ``camera`` check: what a line-following robot's camera will see of the floor markings.

It runs only for a world with floor markings (:func:`worldgen.geometry.markings.floor_markings`: tape lines and
painted patches, visual-only geometry lying on the floor), and judges them with the TurtleBot3 Waffle Pi's camera
(the one the class's line-following lab uses, whatever robot the world is checked with): 640 pixels across a
horizontal field of view of 1.085595 rad (``turtlebot3_waffle_pi.gazebo.xacro``), so a focal length of
320 / tan(0.5428) ≈ 530 px. Seen from :data:`VIEW_DISTANCE` away, a marking ``w`` metres wide spans
``530 · w / 0.5`` pixels: a 5 cm tape about 53 px, a 1 mm line about 1 px, which a colour mask loses to
antialiasing and noise. So:

* a **warning** for each marking narrower than :data:`MIN_PIXELS` there, naming it and its apparent width;
* one **info** line summing up what the camera can see: how many markings, their colours, the narrowest one's
  width in pixels at 0.5 m.

Findings name markings by their SDF link (``floor_markings/track``); for a world built from a spec,
:mod:`worldgen.check.spec_names` turns that into the spec's ``line 'track'``.
"""

from __future__ import annotations

import math

from ..core.findings import Finding
from ..core.materials import color_name
from ..core.scene import Scene
from ..geometry.markings import floor_markings

CAMERA = "the Waffle Pi's camera"
IMAGE_WIDTH = 640                  # px
HORIZONTAL_FOV = 1.085595          # rad
FOCAL_PX = (IMAGE_WIDTH / 2) / math.tan(HORIZONTAL_FOV / 2)
VIEW_DISTANCE = 0.5                # m: about where the camera looks at the floor ahead of a Waffle Pi
MIN_PIXELS = 2.0                   # a marking narrower than this (at VIEW_DISTANCE) is a warning


def apparent_pixels(width: float, distance: float = VIEW_DISTANCE) -> float:
    """How many pixels across the Waffle Pi's image a floor marking ``width`` metres wide spans at ``distance``."""
    return FOCAL_PX * width / distance


def check_camera(scene: Scene, robot: str = "waffle_pi"):
    """The ``camera`` check's :class:`~worldgen.check.checks.Outcome` for ``scene``, or None when the scene has no
    floor markings (nothing to say)."""
    from .checks import Outcome

    markings = floor_markings(scene)
    if not markings:
        return None
    findings = []
    for m in markings:
        px = apparent_pixels(m.width)
        if px < MIN_PIXELS:
            least = MIN_PIXELS * VIEW_DISTANCE / FOCAL_PX
            findings.append(Finding(
                "camera", "warning",
                f"floor marking {m.label} is {_mm(m.width)} wide: {px:.1f} px at {VIEW_DISTANCE:g} m in {CAMERA} "
                f"({IMAGE_WIDTH} px across {HORIZONTAL_FOV:g} rad), too thin for a colour mask to find reliably",
                where=m.label, fix=f"make it at least {math.ceil(least * 1000)} mm wide (floor tape is 19 to 50 mm)"))
    colours = list(dict.fromkeys(color_name(c) if c else "colour not known" for m in markings for c in m.colors))
    narrowest = min(markings, key=lambda m: m.width)
    px = apparent_pixels(narrowest.width)
    note = "; the burger has no camera: line following needs robot model waffle_pi" if robot == "burger" else ""
    findings.append(Finding(
        "camera", "info",
        f"{CAMERA} can see {len(markings)} floor marking{'s' if len(markings) > 1 else ''} "
        f"({', '.join(colours)}); the narrowest, floor marking {narrowest.label}, is {px:.1f} px wide at "
        f"{VIEW_DISTANCE:g} m{note}"))
    return Outcome(findings, {"floor_markings": len(markings), "marking_colors": colours,
                              "narrowest_marking_m": narrowest.width, "narrowest_marking_px": px})


def _mm(width: float) -> str:
    return f"{width * 1000:.1f} mm" if width < 0.1 else f"{width:.2f} m"
