"""Reading the 3D page's pictures in tests: the WebGL canvas' own pixels (``toDataURL``, so no overlay is in
them), the page's top-view frame (world x, y at the canvas' centre, metres per pixel), and masks of a colour and of
shapely geometry on the same pixel grid."""

from __future__ import annotations

import base64
import io

import numpy as np

WALL_CUT = (0x3B, 0x3B, 0x3B)   # the plan's colours (templates/view/page.js)
ROBOT = (0xD6, 0x27, 0x28)
DOOR = (0xE0, 0x8A, 0x1E)
WINDOW = (0x35, 0xB7, 0xD6)


def wait_ready(page) -> None:
    page.wait_for_function("() => window.worldgen && window.worldgen.ready === true")


def canvas_pixels(page) -> np.ndarray:
    """The 3D canvas as an H × W × 3 uint8 array (what WebGL drew, without the HTML overlays)."""
    from PIL import Image

    url = page.evaluate("document.querySelector('#view canvas').toDataURL('image/png')")
    data = base64.b64decode(url.split(",", 1)[1])
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))


def top_view(page) -> tuple[np.ndarray, dict]:
    """Press the page's Top view button; its pixels and frame."""
    page.click("#btn-top")
    frame = page.evaluate("window.worldgen.frame()")
    assert frame["top"], frame
    return canvas_pixels(page), frame


def pixel_centres(shape, frame: dict) -> tuple[np.ndarray, np.ndarray]:
    """World x and y (H × W each) of every pixel's centre in the top view."""
    h, w = shape[:2]
    scale = frame["perPixel"] * w / frame["width"]   # CSS pixels → canvas pixels (the page draws at ratio 1)
    cols = (np.arange(w) + 0.5 - w / 2) * scale + frame["x"]
    rows = frame["y"] - (np.arange(h) + 0.5 - h / 2) * scale
    return np.meshgrid(cols, rows)


def world_to_pixel(x: float, y: float, shape, frame: dict) -> tuple[float, float]:
    """CSS pixel (left, top) in the canvas of world point x, y in the top view."""
    h, w = shape[:2]
    return (w / 2 + (x - frame["x"]) / frame["perPixel"], h / 2 - (y - frame["y"]) / frame["perPixel"])


def colour_mask(pixels: np.ndarray, colour, tolerance: int = 14) -> np.ndarray:
    return (np.abs(pixels.astype(int) - np.asarray(colour)).max(axis=2) <= tolerance)


def geometry_mask(geometry, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    import shapely

    return shapely.contains_xy(geometry, xs, ys)


def ring_share(red: np.ndarray, xs, ys, centre, radius: float, width: float = 0.035, slack: float = 0.02) -> float:
    """The share of ``red`` pixels on the robot's ring (``radius`` to ``radius + width``) around ``centre``."""
    d = np.hypot(xs - centre[0], ys - centre[1])
    on_ring = (d >= radius - slack) & (d <= radius + width + slack)
    return float((red & on_ring).sum() / max(1, red.sum()))
