"""ROS map_server maps: a SLAM map (``map.yaml`` and its PGM/PNG image) becomes straight walls.

The YAML is map_server's own (what ``map_saver`` writes): ``image`` (a path relative to the YAML's folder),
``resolution`` (metres per pixel), ``origin: [x, y, yaw]`` (where the image's bottom-left corner lies in the world;
the yaw must be 0), ``negate`` (0), ``occupied_thresh`` (0.65), ``free_thresh`` (0.196) and ``mode`` (``trinary`` or
``scale``). As map_server reads it, a pixel's occupancy is (255 − p) / 255, where p is the mean of its colour
channels (alpha left out) and is replaced by 255 − p when ``negate`` is set. A pixel whose occupancy is above
``occupied_thresh`` is occupied: a wall. Every other pixel, free (below ``free_thresh``) or unknown (between the two
thresholds), is open floor.

The occupied pixels become walls as an ASCII grid's ``#`` cells do (:func:`worldgen.spec.grid.plan_grid`, one pixel per
cell): runs of pixels, longest first, one pixel (``resolution``) thick, whose boxes cover the pixels exactly; a lone
pixel becomes a square post, the obstacle ``map_post_ROW_COLUMN`` (the image's pixel row and column, from 0 at the
top left). The image is first cropped to its occupied pixels, so a 4000 × 4000 gmapping map that is mostly unknown
costs no more than the building in it.

Two ways in, both through :func:`worldgen.spec.load.load_spec`: the map's YAML itself (a YAML with an ``image`` key is a
map_server map; the world is named after the file), or a spec with ``map: FILE`` (relative to the spec) beside
``name``, ``walls`` (height, material), ``robot``, ``obstacles``, rooms and segments.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..core.errors import SpecError
from ..core.inputs import MAX_SPEC_BYTES, read_text_capped
from . import values
from .grid import plan_grid
from .messages import describe_sized, did_you_mean, metres, suggest_name
from .model import LIMIT, TOP_KEYS, Obstacle, Segment, Spec, WallStyle
from .nodes import Node, compose
from .values import Source

MAP_KEYS = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode")
REQUIRED_KEYS = ("image", "resolution", "origin")
MODES = ("trinary", "scale")     # map_server's "raw" mode has no thresholds, so nothing here says what a wall is
OCCUPIED_THRESH = 0.65           # map_server's defaults (those map_saver writes)
FREE_THRESH = 0.196
IMAGE_SUFFIXES = (".pgm", ".png", ".bmp", ".jpg", ".jpeg", ".gif", ".tif", ".tiff", ".ppm")
POST_PREFIX = "map_post_"
_IMAGE_MODES = ("1", "L", "LA", "P", "PA", "RGB", "RGBA")   # 8-bit grey or colour, as map_server's loader takes
_YAW_EPS = 1e-6                  # map_saver writes a zero yaw as 0.000000 or -0.000000
MAX_MAP_PIXELS = 64_000_000      # width × height of the image (a 8000 × 8000 map); larger ones are refused
MAX_MAP_PIECES = 50_000          # walls and posts one map may become; past it specks are removed, then refused
SPECK_PIXELS = 5                 # occupied blobs (8-connected) smaller than this are specks: SLAM noise


@dataclass(frozen=True)
class MapFile:
    """What a map_server YAML says, checked; ``line`` is the line of its ``image:`` key."""

    path: Path
    image: Path
    resolution: float
    origin: tuple[float, float]
    negate: bool = False
    occupied_thresh: float = OCCUPIED_THRESH
    free_thresh: float = FREE_THRESH
    mode: str = "trinary"
    line: int | None = None


@dataclass(frozen=True)
class Occupancy:
    """A map's occupied pixels as grid rows of ``#`` and ``.``, cropped to the occupied ones: ``rows[0]`` is image
    row ``top``, column 0 is image column ``left``; the crop's bottom-left corner is at ``origin`` (metres)."""

    rows: tuple[str, ...]
    top: int
    left: int
    origin: tuple[float, float]


def is_map_yaml(keys) -> bool:
    """A YAML mapping with an ``image`` key is a map_server map (a spec has no such key)."""
    return "image" in keys


def read_map_yaml(src: Source, root: Node) -> MapFile:
    """Check a map_server YAML's keys (``src.path`` names it in messages); the image is not opened here."""
    keys = root.value
    for key, line in root.key_lines.items():
        if key in MAP_KEYS:
            continue
        hint = f"a map_server map takes: {', '.join(MAP_KEYS)}"
        if key in TOP_KEYS:
            own = Path(src.path or "map.yaml").name
            hint = f"'{key}' belongs in a spec: write one with name: …, map: {own} and {key}: …"
        guess = did_you_mean(key, MAP_KEYS)
        src.fail(f"unknown key '{key}' in the map_server map{guess}", line, hint=hint)
    for key in REQUIRED_KEYS:
        if key not in keys:
            example = {"resolution": "resolution: 0.05", "origin": "origin: [-10.0, -10.0, 0.0]"}.get(key, key)
            src.fail(f"the map_server map has no '{key}'", root.line, hint=f"add {example}")
    yaml_path = Path(src.path or ".")

    node = keys["image"]
    if not isinstance(node.value, str) or not node.value.strip():
        src.fail(f"image must be the image file's name, not {describe_sized(node.value)}", node.line,
                 hint="e.g. image: map.pgm (relative to this file)")
    image = yaml_path.parent / node.value   # an absolute path stays as it is, as map_server reads it
    if not image.is_file():
        beside = yaml_path.parent / Path(node.value).name
        hint = (f"{beside.name} lies beside this file: write image: {beside.name}" if beside.is_file() else
                "map_server looks for the image relative to the YAML's folder; give its name or full path")
        what = "is a folder, not an image" if image.is_dir() else "does not exist"
        src.fail(f"the map's image {image} {what}", node.line, hint=hint)

    resolution = values.length(src, keys["resolution"], "the map's resolution")
    origin = keys["origin"]
    if not isinstance(origin.value, list) or len(origin.value) not in (2, 3):
        src.fail(f"the map's origin must be [x, y, yaw], not {describe_sized(origin.value)}", origin.line,
                 hint="e.g. origin: [-10.0, -10.0, 0.0]: where the image's bottom-left corner lies, in metres")
    x = values.coordinate(src, origin.value[0], "x of the map's origin")
    y = values.coordinate(src, origin.value[1], "y of the map's origin")
    if len(origin.value) == 3:
        yaw = values.angle(src, origin.value[2], "yaw of the map's origin")
        if abs(yaw) > _YAW_EPS:
            src.fail(f"the map's origin has a yaw of {metres(yaw)} rad; worldgen lays a map's pixels along x and y, "
                     "unrotated (amcl and costmap_2d ignore the yaw too)", origin.value[2].line,
                     hint="write 0 for the yaw, or rotate the image itself")

    negate = False
    if "negate" in keys:
        value = keys["negate"].value
        if value not in (0, 1) or isinstance(value, float):   # True and False are 1 and 0
            src.fail(f"negate must be 0 or 1, not {describe_sized(value)}", keys["negate"].line,
                     hint="0: dark pixels are walls (map_saver's maps); 1: light pixels are walls")
        negate = bool(value)
    thresholds = {}
    for key, default in (("occupied_thresh", OCCUPIED_THRESH), ("free_thresh", FREE_THRESH)):
        if key not in keys:
            thresholds[key] = default
            continue
        value = values.number(src, keys[key], key, hint="a fraction from 0 to 1, e.g. 0.65")
        if not 0 <= value <= 1:
            src.fail(f"{key} is {metres(value)}, outside 0–1", keys[key].line,
                     hint=f"thresholds are occupancy fractions; map_server's default is {default}")
        thresholds[key] = value
    if thresholds["free_thresh"] > thresholds["occupied_thresh"]:
        key = "free_thresh" if "free_thresh" in keys else "occupied_thresh"
        src.fail(f"free_thresh {metres(thresholds['free_thresh'])} is above occupied_thresh "
                 f"{metres(thresholds['occupied_thresh'])}", keys[key].line,
                 hint=f"free_thresh must be at most occupied_thresh (map_server's: {FREE_THRESH} and "
                      f"{OCCUPIED_THRESH})")
    mode = "trinary"
    if "mode" in keys:
        if keys["mode"].value == "raw":
            src.fail("mode raw has no thresholds, so it does not say which pixels are walls",
                     keys["mode"].line, hint="use mode: trinary (walls above occupied_thresh)")
        mode = values.text(src, keys["mode"], "the map's mode", MODES)
    return MapFile(path=yaml_path, image=image, resolution=resolution, origin=(x, y), negate=negate,
                   mode=mode, line=node.line, **thresholds)


def load_map_yaml(path: Path) -> MapFile:
    """Read a map_server YAML file (for ``map: FILE``); SpecError names the file and line of a problem."""
    try:
        text = read_text_capped(path, MAX_SPEC_BYTES, SpecError, "map file")
    except UnicodeDecodeError as err:
        raise SpecError(f"is not UTF-8 text ({err.reason} at byte {err.start})", path=path,
                        hint="map: names the map's YAML file (map.yaml), not its image") from None
    except OSError as err:
        raise SpecError(f"cannot be read: {err.strerror}", path=path) from None
    src = Source(str(path))
    root = compose(text, str(path))
    if root is None or not isinstance(root.value, dict) or not is_map_yaml(root.value):
        src.fail("is not a map_server map: it has no 'image' key", root.line if root else None,
                 hint="map: names the YAML map_saver writes (image:, resolution:, origin: …)")
    return read_map_yaml(src, root)


def read_occupancy(m: MapFile) -> Occupancy:
    """The map's occupied pixels (map_server's rules, above), cropped. SpecError (at the ``image:`` line) when the
    image cannot be read or has no occupied pixel."""
    import numpy as np
    from PIL import Image

    def fail(message: str, hint: str) -> SpecError:
        return SpecError(f"the map's image {m.image.name} {message}", path=m.path, line=m.line, hint=hint)

    try:
        with Image.open(m.image) as img:
            if img.mode not in _IMAGE_MODES:
                raise fail(f"has {img.mode} pixels", "save it as an 8-bit grey PGM or PNG, as map_saver does")
            if img.size[0] * img.size[1] > MAX_MAP_PIXELS:
                raise fail(f"has {img.size[0]} × {img.size[1]} pixels, more than the {MAX_MAP_PIXELS:,} worldgen "
                           "reads", "crop the map to the building, or save it at a coarser resolution (see "
                           "Limits in the README)")
            img = img.convert("L" if img.mode == "1" else "RGBA" if img.mode in ("P", "PA") else img.mode)
            pixels = np.asarray(img)
    except Image.DecompressionBombError:
        raise fail("is too large to read safely", "crop the map to the building") from None
    except (OSError, SyntaxError, ValueError) as err:   # Pillow's errors for what is not an image it knows
        raise fail(f"cannot be read as an image ({err})", "give a PGM or PNG map, as map_saver writes it") from None
    # A pixel's colour channels (alpha left out) add up to a whole number; map_server's occupancy of every possible
    # sum, worked out once as map_server works it out (in doubles), then looked up: exact, and light on memory.
    if pixels.ndim == 3:
        channels = 3 if pixels.shape[2] >= 3 else 1
        sums = pixels[:, :, :channels].sum(axis=2, dtype=np.uint16)
    else:
        channels, sums = 1, pixels
    mean = np.arange(255 * channels + 1, dtype=np.float64) / channels
    occupancy = (255.0 - (255.0 - mean if m.negate else mean)) / 255.0
    occupied = (occupancy > m.occupied_thresh)[sums]
    height, width = occupied.shape
    rows_hit, columns_hit = np.flatnonzero(occupied.any(axis=1)), np.flatnonzero(occupied.any(axis=0))
    if not rows_hit.size:
        highest = occupancy[np.unique(sums)].max()
        raise fail(f"has no occupied pixel: none of its {width} × {height} has an occupancy above occupied_thresh "
                   f"{metres(m.occupied_thresh)} (the highest is {highest:.3f})",
                   "check negate (1 when walls are light) and occupied_thresh")
    top, bottom, left, right = int(rows_hit[0]), int(rows_hit[-1]), int(columns_hit[0]), int(columns_hit[-1])
    crop = _bounded(occupied[top:bottom + 1, left:right + 1], fail)
    text = np.where(crop, ord("#"), ord(".")).astype(np.uint8).tobytes().decode("ascii")
    n = right - left + 1
    rows = tuple(text[i:i + n] for i in range(0, len(text), n))
    res = m.resolution
    origin = (round(m.origin[0] + left * res, 9), round(m.origin[1] + (height - 1 - bottom) * res, 9))
    return Occupancy(rows=rows, top=top, left=left, origin=origin)


def pieces(occupied) -> int:
    """At most how many walls and posts the grid planner makes of the ``occupied`` pixels: its runs of two or
    more along rows and along columns, and its lone pixels."""
    import numpy as np

    def runs(grid) -> int:
        padded = np.pad(grid, ((0, 0), (1, 1)))
        starts, ends = np.nonzero(np.diff(padded.astype(np.int8), axis=1) == 1), \
            np.nonzero(np.diff(padded.astype(np.int8), axis=1) == -1)
        return int(((ends[1] - starts[1]) >= 2).sum())

    return runs(occupied) + runs(occupied.T) + lone_pixels(occupied)


def lone_pixels(occupied) -> int:
    """How many occupied pixels have no occupied neighbour left, right, above or below: each becomes a post."""
    import numpy as np

    p = np.pad(occupied, 1)
    return int((occupied & ~(p[:-2, 1:-1] | p[2:, 1:-1] | p[1:-1, :-2] | p[1:-1, 2:])).sum())


def without_specks(occupied, smallest: int = SPECK_PIXELS):
    """``occupied`` without its specks (blobs of fewer than ``smallest`` pixels, 8-connected), and how many
    blobs are left."""
    import numpy as np
    from scipy.ndimage import label

    blobs, _ = label(occupied, structure=np.ones((3, 3), dtype=bool))
    sizes = np.bincount(blobs.ravel())
    sizes[0] = 0   # the free pixels
    keep = sizes[blobs] >= smallest
    return keep, int((sizes[1:] >= smallest).sum())


def _too_many(count: int, fail, how: str = "") -> SpecError:
    return fail(f"would make {how}{count:,} walls and posts even without its specks (blobs under {SPECK_PIXELS} "
                f"pixels), more than the {MAX_MAP_PIECES:,} worldgen builds from one map",
                "clean the noise off the map in an image editor, or crop it to the building (see Limits in the "
                "README)")


def _bounded(occupied, fail):
    """``occupied``, or without specks when it could make more than :data:`MAX_MAP_PIECES` walls and posts;
    ``fail`` (SpecError) when even its blobs, or its lone pixels, are more than that (each needs one at least)."""
    if pieces(occupied) <= MAX_MAP_PIECES:
        return occupied
    cleaned, blobs = without_specks(occupied)
    least = max(blobs, lone_pixels(cleaned))
    if least > MAX_MAP_PIECES:
        raise _too_many(least, fail, "at least ")
    if not cleaned.any():
        raise fail(f"holds nothing but specks (blobs under {SPECK_PIXELS} pixels), too many of them to build",
                   "clean the noise off the map in an image editor")
    return cleaned


def map_parts(m: MapFile, base: WallStyle, line: int | None) -> tuple[list[Segment], list[Obstacle]]:
    """The map's walls (one pixel thick, ``base``'s height and material) and its lone pixels' posts; ``line`` is the
    spec line they are reported at."""
    grid = read_occupancy(m)
    res = m.resolution
    (x0, y0), rows, columns = grid.origin, len(grid.rows), len(grid.rows[0])
    if max(abs(v) for v in (x0, y0, x0 + columns * res, y0 + rows * res)) > LIMIT:
        raise SpecError(f"the map's walls reach farther than {LIMIT:g} m from the origin ({columns} × {rows} pixels "
                        f"of {metres(res)} m from ({metres(x0)}, {metres(y0)}))", path=m.path, line=m.line,
                        hint="check the resolution (metres per pixel) and the origin")
    plan = plan_grid(grid.rows, res, grid.origin, source=str(m.path), max_pieces=None)   # checked here, below
    if len(plan.walls) + len(plan.posts) > MAX_MAP_PIECES:
        raise _too_many(len(plan.walls) + len(plan.posts), lambda message, hint: SpecError(
            f"the map's image {m.image.name} {message}", path=m.path, line=m.line, hint=hint))
    style = WallStyle(thickness=res, height=base.height, material=base.material)
    segments = [Segment(start=a, end=b, style=style, line=line) for a, b in plan.walls]
    posts = [Obstacle(shape="box", at=at, size=(res, res, base.height), material=base.material,
                      name=f"{POST_PREFIX}{grid.top + r}_{grid.left + c}", line=line) for r, c, at in plan.posts]
    return segments, posts


def map_spec(src: Source, root: Node) -> Spec:
    """A map_server YAML read as a whole spec: the world is named after the file; default wall height and material;
    no robot (``worldgen validate`` then spawns it at the origin)."""
    m = read_map_yaml(src, root)
    segments, posts = map_parts(m, WallStyle(), m.line)
    return Spec(name=suggest_name(m.path.stem), segments=tuple(segments), obstacles=tuple(posts),
                source=src.path)


def spec_map_parts(src: Source, node: Node, base: WallStyle) -> tuple[list[Segment], list[Obstacle]]:
    """A spec's ``map: FILE``: the map's walls, with the spec's wall height and material."""
    if not isinstance(node.value, str) or not node.value.strip():
        src.fail(f"map must name a map_server YAML file, not {describe_sized(node.value)}", node.line,
                 hint="e.g. map: lab.yaml (relative to this spec), the file map_saver wrote")
    path = Path(src.path or ".").parent / node.value
    if path.suffix.lower() in IMAGE_SUFFIXES:
        src.fail(f"map names an image ({path.name}); it must name the map's YAML, which gives its resolution "
                 "and origin", node.line, hint=f"write map: {path.with_suffix('.yaml').name}, the file map_saver "
                                                "wrote beside the image")
    if not path.is_file():
        src.fail(f"the map file {path} {'is a folder' if path.is_dir() else 'does not exist'}", node.line,
                 hint="map: is relative to this spec's folder")
    return map_parts(load_map_yaml(path), base, node.line)


