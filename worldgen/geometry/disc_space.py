"""Where a disc can be among the obstacles: the free space shrunk by a radius (per radius, computed once), which
part of it is the outside, and the radius at which a point is cut off from the outside (bisected), for
:mod:`.enclosure`'s search for ways out.

With very many obstacles most radii are decided from the obstacles near the point (:func:`_closed_by`): what a
window's parts, each grown by a little less than the radius, close off round the point, all the obstacles grown by
the whole radius close off too. The radii that window does not show cut off are guessed open and confirmed after
the bisection (:meth:`Space.critical_radius`), so every radius comes out as computing each from its own space
would give.

Plain numbers in, plain numbers out: shapely and numpy (imported when first used).
"""

from __future__ import annotations

import hashlib
import math
import threading
from collections import OrderedDict

from .ahead import in_thread, outcome
from .slices import SLIVER, Footprint
from .growth import SMALL, cluster_labels, grown, unite

MAX_GAP = 8.0          # openings are searched up to this wide, or up to the walls' own extent when that is more
WIDTH_TOLERANCE = 0.005  # the critical radius is bisected to half this
MANY_SHAPES = 2000     # past this many footprints, one gap is listed (then: "there may be more")

UNIONS_KEPT = 4   # unions of many footprints kept by their content (see obstacle_union)
_UNIONS: "OrderedDict[str, object]" = OrderedDict()
_UNIONS_LOCK = threading.Lock()


def obstacle_union(prints: list[Footprint]):
    """The footprints united and grown by :data:`SLIVER` (empty geometry when there are none). Many footprints:
    the union is kept by their content (the last :data:`UNIONS_KEPT`), as the same ones come again — a world
    checked from each of its rooms, a band of upright walls cut at the LiDAR's height and across the robot's
    (a random 200 × 200 grid: 9 000 touching boxes, about 1.5 s a union)."""
    import shapely

    if len(prints) <= SMALL:   # few: as GEOS does it (the same region; vertex for vertex as before)
        return shapely.union_all([p.geometry for p in prints]).buffer(SLIVER, quad_segs=2)
    geometries = [p.geometry for p in prints]
    key = hashlib.sha256(b"".join(shapely.to_wkb(geometries))).hexdigest()
    with _UNIONS_LOCK:
        if key in _UNIONS:
            _UNIONS.move_to_end(key)
            return _UNIONS[key]
    united = unite(shapely.buffer(geometries, SLIVER, quad_segs=2))
    with _UNIONS_LOCK:
        _UNIONS[key] = united
        while len(_UNIONS) > UNIONS_KEPT:
            _UNIONS.popitem(last=False)
    return united


_FREE: "OrderedDict[tuple, tuple]" = OrderedDict()   # (id(obstacles), frame) -> (obstacles, parts, outside)


def _free_space(obstacles, frame) -> tuple:
    """(the parts of the free space in ``frame``, the one touching the frame): kept for the last
    :data:`UNIONS_KEPT` obstacle unions (the same object, from :func:`obstacle_union`, for each room checked)."""
    key = (id(obstacles), tuple(frame.bounds))
    with _UNIONS_LOCK:
        kept = _FREE.get(key)
    if kept is not None and kept[0] is obstacles:
        return kept[1], kept[2]
    parts, outside = _parts_and_outside(frame.difference(obstacles), frame)
    with _UNIONS_LOCK:
        _FREE[key] = (obstacles, parts, outside)   # holding the obstacles keeps their id theirs
        while len(_FREE) > UNIONS_KEPT:
            _FREE.popitem(last=False)
    return parts, outside


def _parts_and_outside(free, frame) -> tuple:
    parts = components(free)
    return parts, next((c for c in parts if reaches_outside(c, frame)), None)


def components(geometry) -> list:
    """The polygons of ``geometry`` with an area, in its order (tested all at once: a free space among 10 000
    posts has as many)."""
    import numpy as np
    import shapely

    parts = shapely.get_parts(geometry)
    with np.errstate(over="ignore", invalid="ignore"):   # a spawn 1000 km out: inf, quietly as one by one
        return list(parts[(shapely.get_type_id(parts) == 3) & (shapely.area(parts) > 0)])


def reaches_outside(component, frame) -> bool:
    return component is not None and component.exterior.distance(frame.exterior) < 1e-9


class Family:
    """What the spaces of one obstacle union share, plugged or not: the unplugged obstacles grown per radius, the
    radius first asked for under each rounded key (the one they are grown by), and, for very many obstacles, their
    parts in an STRtree (for :meth:`Space.closed_near`)."""

    def __init__(self, base):
        import shapely

        self.base = base
        self.grown: dict[float, object] = {}
        self.radii: dict[float, float] = {}
        self.parts = shapely.get_parts(base)
        self.many = len(self.parts) > SMALL
        self.local = len(self.parts) > MANY_SHAPES   # so many that a window round a point is worth a try
        self.tree = shapely.STRtree(self.parts) if self.local else None
        self.areas = shapely.area(shapely.envelope(self.parts)) if self.local else None
        self.root: Space | None = None   # the space of these obstacles without plugs (see Space._outside)


LOCAL_REACH = 0.25     # m: the first window round a point reaches this far beyond the radius (then 4, 16, … times)
LOCAL_FEW = 64         # a window holding more parts than this is tried with its largest ones first (walls first)
LOCAL_SHARE = 8        # … and with all of them only while they are at most this share of all (else: the whole
LOCAL_MOST = 300       # space decides) and at most this many
PROOF_SHRINK = 0.98    # the parts grown by this share of the radius lie inside the ones grown by all of it (below)
PROOF_MARGIN = 1e-7    # m: more than any rounding of the union and difference, less than anything decided by it


class Space:
    """Where the centre of a disc of radius ``r`` can be (the free space shrunk by ``r``), per radius (cached),
    and which part of it is the outside (the part touching the frame).

    A disc of radius ``r`` passes an opening exactly when the opening is wider than ``2·r``, whatever the walls'
    thickness, so the radius at which a point is cut off from the outside measures the widest way out. A point
    is reached from the outside at radius ``r`` when an outside disc covers it.
    """

    def __init__(self, obstacles, frame, plugs: tuple = (), base: Space | None = None, limit: float = MAX_GAP):
        """``obstacles``: their union, or (a plugged space) a function that unites them when first needed."""
        self._obstacles, self.frame, self.plugs, self.limit = obstacles, frame, plugs, limit
        self.family = Family(obstacles) if base is None else base.family   # the obstacles before any plug
        if base is None and not plugs:
            self.family.root = self
        self.base = self.family.base
        self._cut_outside: dict = {}   # point -> the outside at radius 0 as cut for it by _outside
        self._cache: dict[float, tuple] = {}
        self._radii: dict[float, float] = {}   # the radius first asked for under each key: the one used
        self._shown: dict[tuple, bool] = {}    # (point, key) -> whether closed_near showed it cut off
        self._plugged: dict[int, tuple] = {}   # id(plug) -> (plug, the space it was first added to this one in)
        self._ahead: dict[float, tuple] = {}   # key -> (radius, future of _computed): started by _compute_ahead

    @property
    def obstacles(self):
        """The obstacles, plugs included, united: for a plugged space when first asked for (the last one of a
        search is only asked whether the point is still reached at radius 0, which :meth:`_outside` answers
        without them)."""
        if callable(self._obstacles):
            self._obstacles = self._obstacles()
        return self._obstacles

    def radius(self, r: float) -> tuple[float, float]:
        """(the cache key of ``r``, the radius that stands for every radius of that key: the first asked for)."""
        key = round(r, 6)
        return key, self._radii.setdefault(key, r)

    def grown(self, r: float):
        """The obstacles (plugs included) grown by ``r``. Many obstacles: the unplugged ones are grown once per
        radius for every plugged space, the plugs added to that. Few: GEOS's buffer of them all."""
        import shapely

        if not self.family.many:
            return self.obstacles.buffer(r, quad_segs=8) if r > 0 else self.obstacles
        key = round(r, 6)
        if key not in self.family.grown:
            self.family.grown[key] = grown(self.base, self.family.radii.setdefault(key, r), quad_segs=8)
        if not self.plugs:
            return self.family.grown[key]
        plugs = shapely.buffer(list(self.plugs), r, quad_segs=8) if r > 0 else list(self.plugs)
        return unite([*shapely.get_parts(self.family.grown[key]), *plugs])

    def at(self, r: float):
        key, r = self.radius(r)
        if key not in self._cache:
            ahead = _taken_ahead(self, key, r)
            if ahead is not None:
                self._cache[key] = ahead
            elif key == 0 and not self.plugs:   # the free space itself: the same for every room of a world
                self._cache[key] = _free_space(self.obstacles, self.frame)
            else:
                self._cache[key] = _parts_and_outside(self.frame.difference(self.grown(r)), self.frame)
        return self._cache[key]

    def cut_off(self, point: tuple[float, float], r: float, guessed: list | None = None) -> bool:
        """Whether no disc of radius ``r`` from the outside covers ``point``: from the space at ``r`` (:meth:`at`),
        unless the obstacles near the point show it cut off (:meth:`closed_near`, very many obstacles). With
        ``guessed`` (a bisection), a radius they do not show cut off, not computed yet, is taken as not cutting off
        and noted there, to be confirmed (:meth:`_confirmed`)."""
        key, r = self.radius(r)
        if self.family.many and (key or self.plugs):   # the radius the obstacles are grown by under this key
            self.family.radii.setdefault(key, r)
        if key not in self._cache and self.family.local and r > 0:
            if (point, key) not in self._shown:
                self._shown[(point, key)] = self.closed_near(point, r)
            if self._shown[(point, key)]:
                return True
            if guessed is not None:
                guessed.append(r)
                return False
        return self._reach(point, r) > r + 1e-9

    def _reach(self, point: tuple[float, float], r: float) -> float:
        """How far ``point`` is from the outside at radius ``r`` (inf when nothing is outside)."""
        import shapely

        outside = self._outside(r, point)
        return math.inf if outside is None else outside.distance(shapely.Point(point))

    def _outside(self, r: float, point: tuple[float, float]):
        """The outside at radius ``r``, for the distance from ``point`` to it alone (:meth:`_reach`). A plugged
        space of very many obstacles at radius 0 not computed yet: the unplugged free space less the plugs, cut for
        this point (:func:`_cut_outside`), without uniting thousands of obstacles and cutting them out of the frame
        again for each plug. The spaces the neck is found in are computed whole (:meth:`at`), vertex for vertex as
        before: among equally near points (posts on a regular grid) the first in their order is taken."""
        key, r = self.radius(r)
        family = self.family
        if key != 0 or key in self._cache or not self.plugs or not family.many or family.root is None or \
                r != 0 or family.radii.setdefault(key, r) != 0:
            return self.at(r)[1]
        if point not in self._cut_outside:
            self._cut_outside[point] = _cut_outside(family.root.at(0.0)[0], self.plugs, self.frame, point)
        return self._cut_outside[point]

    def closed_near(self, point: tuple[float, float], r: float) -> bool:
        """True when the obstacles near ``point`` (more than :data:`MANY_SHAPES` parts) already cut it off at radius
        ``r``, as :meth:`cut_off` finds from the whole space; False when that is not shown here (:meth:`at` decides
        then). Shown by :func:`_closed_by` with the parts in a window round the point, 4 times wider each try (its
        largest parts first), while it holds at most 1/:data:`LOCAL_SHARE` of them: what the parts of a window
        close off, all of them do."""
        import numpy as np
        import shapely

        family = self.family
        if r <= 0 or not family.local:
            return False
        (x, y), h = point, r + LOCAL_REACH
        x0, y0, x1, y1 = self.base.bounds
        while True:
            near = np.sort(family.tree.query(shapely.box(x - h, y - h, x + h, y + h)))
            if len(near) > LOCAL_FEW:
                largest = np.sort(near[np.argsort(-family.areas[near], kind="stable")[:LOCAL_FEW]])
                if _closed_by([*family.parts[largest], *self.plugs], point, r):
                    return True
            if LOCAL_SHARE * len(near) > len(family.parts) or len(near) > LOCAL_MOST:
                return False
            if _closed_by([*family.parts[near], *self.plugs], point, r):
                return True
            if x - h <= x0 and y - h <= y0 and x + h >= x1 and y + h >= y1:
                return False
            h = r + 4 * (h - r)

    def critical_radius(self, point) -> tuple[float, float] | None:
        """The radii just below and just above (to :data:`WIDTH_TOLERANCE`/2) the one that cuts ``point``
        off; None when even ``limit``/2 does not, (0, 0) when it is cut off already.

        Bisected with the radii that do not cut the point off guessed (all but the last need no space of their
        own), then confirmed; a guess found wrong is known then, and the bisection runs again: the radii are the
        ones each decided in turn from its own space would give. The first confirmation computes the space the
        next bisection would need meanwhile (:meth:`_compute_ahead`): the first guesses are the likeliest wrong."""
        ahead = True
        while True:
            guessed: list = []
            bounds = self._bisect(lambda r, guess: self.cut_off(point, r, guessed if guess else None))
            if bounds is None or not guessed or self._confirmed(point, guessed, bounds[0], ahead):
                return bounds
            ahead = False

    def _bisect(self, cut) -> tuple[float, float] | None:
        """The bisection, with ``cut(r, guess)`` saying whether radius ``r`` cuts the point off (``guess``: a
        radius not shown cut off may be guessed open)."""
        if cut(0.0, False):
            return 0.0, 0.0
        if not cut(self.limit / 2, False):   # a disc that passes there passes every smaller opening too
            return None
        lo, hi = 0.0, 0.05
        while not cut(hi, True):
            if hi >= self.limit / 2:
                return None
            lo, hi = hi, min(hi * 2, self.limit / 2)
        while hi - lo > WIDTH_TOLERANCE / 2:
            mid = (lo + hi) / 2
            lo, hi = (lo, mid) if cut(mid, True) else (mid, hi)
        return lo, hi

    def _confirmed(self, point, guessed: list, lo: float, ahead: bool = False) -> bool:
        """Whether every radius in ``guessed`` indeed does not cut ``point`` off. The largest is computed (the
        bisection's lower end ``lo``: its space is needed anyway). A smaller radius ``s`` below a computed one
        ``r`` the point is reached at, from an outside point at distance ``d``, is not computed when ``s`` ≤ 98 %
        of ``r`` and ``d`` ≤ 99.5 % of ``r`` less 1.02 % of ``s``: a disc of radius ``s`` then fits wherever one
        of ``r`` did (GEOS's grown parts lie between 99.5 % and 101 % of the true ones), and one on the way from
        that outside point towards ``point`` covers it. A wrong guess ends the check at once: its space is kept,
        so the bisection turns the other way there next time, and the smaller guesses are settled then, from a
        larger lower end than this one's (the guesses only grow along the way, the lower end of the bisection);
        computing them now, one full space each, could only repeat what that proves. With ``ahead``, the first
        space computed here has the next bisection's computed beside it (:meth:`_compute_ahead`)."""
        ref = None if lo in guessed else (lo, self._reach(point, lo))   # lo computed and not cutting off already
        for s in sorted(set(guessed), reverse=True):
            if ref is not None and s <= PROOF_SHRINK * ref[0] - PROOF_MARGIN and \
                    ref[1] <= 0.995 * ref[0] - 0.0102 * s - 2 * PROOF_MARGIN:
                continue
            if ahead:
                self._compute_ahead(point, s)
                ahead = False
            d = self._reach(point, s)
            if d > s + 1e-9:
                return False
            ref = (s, d)
        return True

    def _compute_ahead(self, point, guess: float) -> None:
        """Very many obstacles: start computing, in a thread of its own, the space the next bisection would
        compute first were ``guess`` (about to be computed) found to cut ``point`` off after all (its lower end,
        a guess between the last one below and this one), so that both are computed at once. Foreseen without
        computing any space (:func:`_foreseen`); taken by :meth:`at` only when asked for at the very radius
        foreseen (:func:`_taken_ahead`)."""
        if not self.family.local or round(guess, 6) in self._cache:
            return
        r = _foreseen(self, point, guess)
        key = round(r, 6) if r is not None else None
        if r is not None and key not in self._cache and key not in self._ahead and self._radii.get(key, r) == r:
            self._ahead[key] = (r, in_thread(lambda: _computed(self, key, r)))

    def plugged(self, plug) -> Space:
        """This space with ``plug`` added to the obstacles. The same plug again (the way out the search followed,
        closed for the next round): a new space, but the obstacles united and the free space among them (radius
        0, the first a search asks for) as computed the first time. The obstacles are united when first needed."""
        kept = self._plugged.get(id(plug))
        if kept is not None and kept[0] is plug:
            first = kept[1]
            space = Space(lambda: first.obstacles, self.frame, first.plugs, self, self.limit)
            if first._radii.get(0.0) == 0.0 and 0.0 in first._cache:
                space._radii[0.0], space._cache[0.0] = 0.0, first._cache[0.0]
            space._cut_outside = dict(first._cut_outside)
            return space
        space = Space(lambda: _with_plug(self.obstacles, plug), self.frame, (*self.plugs, plug), self, self.limit)
        self._plugged[id(plug)] = (plug, space)   # holding the plug keeps its id its own
        return space


def _foreseen(space: Space, point, guess: float) -> float | None:
    """The lower end of the next bisection were ``guess`` found to cut ``point`` off, when that is a guess (the
    radius its confirmation computes first): the bisection again, on the radii computed and what the obstacles
    near the point show (:meth:`Space.closed_near`, kept as the bisection keeps it). None when it would need a
    space not computed yet to get there."""
    guessed: list = []

    def cut(r: float, guess_open: bool) -> bool:
        key = round(r, 6)
        if r == guess:
            return True
        if key in space._cache or (key == 0 and r == 0 and point in space._cut_outside):
            return space.cut_off(point, r)
        if r > 0 and (point, key) not in space._shown:
            space._shown[(point, key)] = space.closed_near(point, r)
        if r > 0 and space._shown[(point, key)]:
            return True
        if r > 0 and guess_open:
            guessed.append(r)
            return False
        raise _Unforeseen

    try:
        bounds = space._bisect(cut)
    except _Unforeseen:
        return None
    return bounds[0] if bounds is not None and bounds[0] in guessed else None


def _computed(space: Space, key: float, r: float) -> tuple:
    """(the radius the obstacles are grown by, their growth kept when this began, else None and the growth
    computed here, and the space at ``r``) as :meth:`Space.at` computes it for very many obstacles, writing
    nothing shared (run in a thread of its own)."""
    import shapely

    by = space.family.radii.get(key, r)
    known = space.family.grown.get(key)
    grown_here = grown(space.base, by, quad_segs=8) if known is None else None
    obstacles = known if grown_here is None else grown_here
    if space.plugs:
        plugs = shapely.buffer(list(space.plugs), r, quad_segs=8) if r > 0 else list(space.plugs)
        obstacles = unite([*shapely.get_parts(obstacles), *plugs])
    return by, known, grown_here, _parts_and_outside(space.frame.difference(obstacles), space.frame)


def _taken_ahead(space: Space, key: float, r: float) -> tuple | None:
    """The space at ``r`` computed ahead (:meth:`Space._compute_ahead`), when it is the one :meth:`Space.at`
    would compute now: the same radius, the obstacles grown by the same radius (the same growth, or none kept yet:
    then it is kept). None otherwise, or when it failed (then computed there, failing as it would)."""
    ahead = space._ahead.pop(key, None)
    if ahead is None or ahead[0] != r:
        return None
    done = outcome(ahead[1])
    if done is None:
        return None
    by, known, grown_here, computed = done
    family = space.family
    if known is not None:
        return computed if family.grown.get(key) is known else None
    if key in family.grown or family.radii.setdefault(key, r) != by:
        return None
    family.grown[key] = grown_here
    return computed


class _Unforeseen(Exception):
    """The next bisection needs a space not computed yet to go on: nothing is started ahead."""


def _with_plug(obstacles, plug):
    """``obstacles`` (a union) and ``plug`` united."""
    import shapely

    parts = shapely.get_parts(obstacles)
    return shapely.union_all([obstacles, plug]) if len(parts) <= SMALL else unite([*parts, plug])


def _cut_outside(parts: list, plugs: tuple, frame, point):
    """The part touching ``frame`` of the free space ``parts`` less ``plugs`` (None when none does), as far as
    the distance from ``point`` to it goes: only the parts the plugs meet are cut, each with only the holes that
    can matter (:func:`_holes_kept`)."""
    import shapely

    cutter = shapely.union_all(list(plugs))
    shapely.prepare(cutter)
    hit = shapely.intersects(cutter, list(parts)) if len(parts) else []
    for part, cut in zip(parts, hit):
        for piece in components(_holes_kept(part, cutter, point).difference(cutter)) if cut else [part]:
            if reaches_outside(piece, frame):
                return piece
    return None


def _holes_kept(part, cutter, point):
    """``part`` with its holes filled but those the cutter meets, those within 1 µm of ``point`` and those
    touching another of its rings: cut by ``cutter``, it falls into the same pieces (a filled hole joins the one
    piece round it: the cutter keeps clear of it, and its ring meets no other), the point in the same one, and
    the distance from the point to each piece it is not in stays (a filled hole lies within the piece round it).
    The free space among 10 000 posts has a hole for each: cutting a few instead of all is 0.2 s less."""
    import shapely

    rings = shapely.get_rings(part)
    holes = shapely.polygons(rings[1:])
    if len(holes) == 0:
        return part
    keep = shapely.intersects(cutter, holes) | (shapely.distance(holes, shapely.Point(point)) <= 1e-6)
    keep |= shapely.intersects(rings[0], rings[1:])
    a, b = shapely.STRtree(rings[1:]).query(rings[1:], predicate="intersects")
    keep[a[a != b]] = True
    if keep.all():
        return part
    return shapely.Polygon(rings[0], list(rings[1:][keep]))


def _closed_by(parts: list, point: tuple[float, float], r: float) -> bool:
    """Whether ``parts`` (some of the obstacles, plugs included), each grown by :data:`PROOF_SHRINK` of ``r``, cut
    ``point`` off at ``r``: every free piece within ``r`` of it lies in a hole of the union of some of them (a
    cluster of grown parts that meet). All obstacles grown by ``r`` then close each such piece off too, and no
    disc centre within ``r`` of the point is outside: a part grown by all of ``r`` covers it grown by that much
    less with room to spare (GEOS's arcs lie within 0.5 % of the radius inside the true ones, its simplification
    of a part's outline adds at most 1 % of it), whatever the rounding; a piece that nearly reaches ``r`` counts."""
    import numpy as np
    import shapely

    g = r * PROOF_SHRINK - PROOF_MARGIN
    if g <= 0 or not parts:
        return False
    reach = r + 1e-9 + PROOF_MARGIN
    x, y = point
    box, here = shapely.box(x - reach, y - reach, x + reach, y + reach), shapely.Point(point)
    grown_parts = shapely.buffer(np.asarray(parts, dtype=object), g, quad_segs=8)
    free = box.difference(shapely.union_all(grown_parts[shapely.intersects(grown_parts, box)]))
    pieces = [c for c in components(free) if c.distance(here) <= reach]
    if not pieces:
        return True
    label = cluster_labels(grown_parts)
    bounds = shapely.bounds(grown_parts)
    held: dict = {}
    for piece in pieces:
        q = piece.representative_point()
        inside = (bounds[:, 0] < q.x) & (bounds[:, 1] < q.y) & (bounds[:, 2] > q.x) & (bounds[:, 3] > q.y)
        if not any(_in_hole(held, grown_parts, label, k, q) for k in np.unique(label[inside])):
            return False
    return True


def _in_hole(held: dict, grown_parts, label, k: int, q) -> bool:
    """Whether ``q`` lies, clear of it, in a hole of the union of the grown parts labelled ``k`` (kept in
    ``held``)."""
    import shapely

    if k not in held:
        held[k] = shapely.get_parts(shapely.union_all(grown_parts[label == k]))
    return any(shapely.Polygon(p.exterior).contains(q) and p.distance(q) > PROOF_MARGIN for p in held[k])
