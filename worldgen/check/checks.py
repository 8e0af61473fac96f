"""The validation checks: each turns a scene (and, for the simulated ones, numbers measured in pybullet) into
findings a student can act on, plus metrics a program can read.

Geometric checks run here, in the calling process: ``parse`` (the reader's own findings), ``enclosed`` (see
:mod:`worldgen.geometry.enclosure`) and ``spawn-clear``; so does the optional ``sdformat`` (libsdformat's own check, in a
child process of its own). The simulated checks — ``settle``, ``lidar``, ``spin`` and
``stop-at-wall`` — run together in one child process per world (:mod:`worldgen.check.sim_job`), which returns
what it measured as a typed record (:mod:`worldgen.check.sim_results`); :func:`sim_findings` judges it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from pathlib import Path

from ..core.findings import Finding
from ..core.scene import Scene
from ..robots.body import RobotBody, robot_body  # noqa: F401  (the checks' robot; validate imports it from here)
from .sim_job import STOP_TARGET
from .sim_results import Scanned, Settled, SimNumbers, Stopped
from ..geometry.enclosure import enclosure, passage_width
from ..geometry.slices import footprints_between, ground_under
from .sdformat import messages, sdformat_check

GEOMETRIC_CHECKS = ("parse", "enclosed", "spawn-clear")
SIM_CHECKS = ("settle", "lidar", "spin", "stop-at-wall")
CLIMB = 0.010            # TurtleBot3's threshold of climbing: anything lower is not in the robot's way
SPIN_DRIFT_LIMIT = 0.05  # m: spinning in place must keep the robot within this of where it started
STOP_TOLERANCE = 0.05    # m: and must end within this of it
TILT_LIMIT = 10.0        # degrees: an upright robot after settling
GROUND_LIMIT = 0.02      # m: base_footprint within this of the floor after settling
FLOOR_STEP = 0.1         # m: a slab no higher than this under the spawn is the floor the robot stands on


# --------------------------------------------------------------------------------------------------- robot

def placed_footprint(body: RobotBody, spawn: tuple[float, float, float]):
    """The robot's footprint (shapely Polygon) at world pose ``spawn`` = (x, y, yaw)."""
    import shapely

    x, y, yaw = spawn
    c, s = math.cos(yaw), math.sin(yaw)
    return shapely.Polygon([(x + c * px - s * py, y + s * px + c * py) for px, py in body.footprint])


# ----------------------------------------------------------------------------------------------- outcomes

@dataclass
class Outcome:
    """What one check says: its findings and the metrics it measured."""

    findings: list[Finding]
    metrics: dict


def _xy(p) -> str:
    return f"({_coordinate(p[0])}, {_coordinate(p[1])})"


def _coordinate(value: float) -> str:
    """Centimetres for a coordinate as people write them; 3 significant digits for absurdly large ones."""
    return f"{value:.2f}" if abs(value) < 1e6 else f"{value:.3g}"


# ------------------------------------------------------------------------------------------- parse

def check_parse(scene: Scene) -> Outcome:
    """The reader's findings, carried over as they are, and what the scene holds."""
    kinds: dict[str, int] = {}
    for s in scene.shapes:
        kinds[s.kind] = kinds.get(s.kind, 0) + 1
    return Outcome(list(scene.findings), {"sdf_version": scene.sdf_version, "shapes": len(scene.shapes),
                                          "shape_kinds": dict(sorted(kinds.items())),
                                          "models": len(scene.models)})


# ------------------------------------------------------------------------------------------------ ground

def floor_under(scene: Scene, spawn: tuple[float, float, float]) -> tuple[float, dict]:
    """The floor height at the spawn point: 0, or the top of a floor slab under it no higher than a step the
    robot would be lifted onto (Gazebo's asphalt_plane is a 0.1 m box half sunk into the ground)."""
    height, label = ground_under(scene, spawn[:2], FLOOR_STEP)
    return height, {"floor_height_m": height, "floor": label}


# ---------------------------------------------------------------------------------------------- enclosed

def check_enclosed(scene: Scene, spawn: tuple[float, float, float], body: RobotBody, ground: float = 0.0
                   ) -> Outcome:
    """The spawn lies in a region the walls close at LiDAR height (above the floor at ``ground``);
    otherwise, where each way out is."""
    height = ground + (body.lidar_height if body.lidar_height is not None else min(body.height, 0.182))
    found = enclosure(scene, spawn[:2], height)
    metrics = {"enclosed": found.enclosed, "slice_height_m": height,
               "gaps": [g.to_dict() for g in found.gaps],
               "enclosed_area_m2": found.region_area,
               "enclosed_bounds": list(found.region_bounds) if found.region_bounds else None,
               "nearest_wall_m": found.nearest}
    where = f"spawn {_xy(spawn)}"
    notes = [Finding("enclosed", "warning" if note.startswith("mesh ") else "info", note, where=where,
                     fix="re-export the mesh as a closed surface (walls as solids, not loose triangles)"
                     if note.startswith("mesh ") else None) for note in found.notes]
    outcome = _enclosed_verdict(found, spawn, body, metrics, height, where, scene, ground)
    outcome.findings[:0] = notes
    return outcome


def _enclosed_verdict(found, spawn, body: RobotBody, metrics: dict, height: float, where: str, scene: Scene,
                      ground: float) -> Outcome:
    if found.inside is not None:
        metrics["spawn_inside"] = found.inside
        return Outcome([Finding(
            "enclosed", "error", f"the spawn point {_xy(spawn)} is inside {found.inside or 'an obstacle'}",
            where=where, fix="move the spawn pose (launch x_pos/y_pos, spec robot.at or --spawn) onto free floor "
                             "inside the room")], metrics)
    if found.enclosed:
        return Outcome([], metrics)
    if not found.has_walls:
        return Outcome([Finding(
            "enclosed", "error",
            f"no walls around the spawn: nothing in this world stands at LiDAR height ({height:.3f} m)",
            where=where, fix="add walls round the robot (a room in the spec, or walls in the Building Editor), "
                             "or include the model that holds them (is a --model-path missing?)")], metrics)
    if not found.gaps:
        if found.rooms:
            x0, y0, x1, y1 = found.rooms[0]
            metrics["nearest_room"] = list(found.rooms[0])
            centre = ((x0 + x1) / 2, (y0 + y1) / 2)
            message = (f"the spawn {_xy(spawn)} is outside the walls: the nearest closed room spans "
                       f"x {x0:.2f} … {x1:.2f}, y {y0:.2f} … {y1:.2f} (centre {_xy(centre)})")
            fix = "move the spawn into that room (launch x_pos/y_pos, spec robot.at or --spawn)"
        else:
            message = (f"the walls do not surround the spawn: the nearest is {found.nearest:.2f} m away and no "
                       "opening, however wide, would close the region round it")
            fix = "put the spawn inside a room, or close the room round it"
        return Outcome([Finding("enclosed", "error", message, where=where, fix=fix)], metrics)
    # The plane is open. Can the robot itself pass each gap? Its body spans the floor to its top, so a window
    # sill or an obstacle under the beams may hold it in while the beams still pass.

    band = footprints_between(scene, ground + CLIMB, ground + body.height, also=(height,))
    passes = [passage_width(band, gap) >= body.width for gap in found.gaps]
    exits = [g for g, ok in zip(found.gaps, passes) if ok]
    leaks = [g for g, ok in zip(found.gaps, passes) if not ok]
    metrics["robot_enclosed"] = not exits
    metrics["gaps"] = [{**g.to_dict(), "robot_passes": ok} for g, ok in zip(found.gaps, passes)]
    findings = [Finding(
        "enclosed", "error",
        f"the room is open: a {_width(gap.width)} gap at {_xy(gap.centre)}{_between(gap)}; the {body.name} "
        f"({body.width:.3f} m wide) can drive out through it",
        where=f"gap from {_xy(gap.ends[0])} to {_xy(gap.ends[1])}",
        fix="close the gap (join the walls there, or remove the opening), or move the spawn into a closed room")
        for gap in exits]
    findings += [Finding(
        "enclosed", "warning",
        f"LiDAR beams leave the room through a {_width(gap.width)} opening at {_xy(gap.centre)}{_between(gap)} "
        f"({height:.3f} m above the ground); the {body.name} cannot pass "
        + ("(too narrow)" if gap.width < body.width else "(something below or above the beams blocks it)"),
        where=f"opening from {_xy(gap.ends[0])} to {_xy(gap.ends[1])}",
        fix="close it at LiDAR height if the robot should see walls all round, or handle the readings that "
            "see nothing")
        for gap in leaks]
    if found.more:
        findings.append(Finding(
            "enclosed", "error" if exits else "warning",
            f"there may be more gaps: the search stops after the {len(found.gaps)} above",
            fix="close these and validate again"))
    return Outcome(findings, metrics)


def _width(width: float) -> str:
    return f"{width:.2f} m" if width >= 0.1 else f"{width * 1000:.0f} mm"


def _between(gap) -> str:
    return f" between {' and '.join(gap.between)}" if gap.between else ""


# ------------------------------------------------------------------------------------------- spawn-clear

def check_spawn_clear(scene: Scene, spawn: tuple[float, float, float], body: RobotBody, ground: float = 0.0
                      ) -> Outcome:
    """The robot's footprint at the spawn pose touches no wall or obstacle between the floor at ``ground``
    (above the climbing threshold) and the robot's top; how far the nearest is; room to turn in place."""
    import numpy as np
    import shapely

    robot = placed_footprint(body, spawn)
    prints = footprints_between(scene, ground + CLIMB, ground + body.height)
    centre = shapely.Point(spawn[:2])
    metrics: dict = {"min_clearance_m": None, "nearest_obstacle": None, "turn_clearance_m": None}
    if not prints:
        return Outcome([], metrics)
    geometries = [p.geometry for p in prints]   # measured in one call each (a grid: thousands of footprints)
    with np.errstate(over="ignore"):   # a spawn 1000 km out: inf, as one by one
        distances = list(zip(shapely.distance(geometries, robot).tolist(), (p.label for p in prints)))
        turn = float(shapely.distance(geometries, centre).min()) - body.turn_radius
    clearance, nearest = min(distances)
    metrics.update(min_clearance_m=clearance, nearest_obstacle=nearest, turn_clearance_m=turn)
    where = f"spawn {_xy(spawn)}, yaw {spawn[2]:.2f}"
    hit = sorted({label for d, label in distances if d <= 0})
    if hit:
        metrics["overlap_m2"] = max(p.geometry.intersection(robot).area for p in prints)
        return Outcome([Finding(
            "spawn-clear", "error",
            f"the {body.name} spawns inside {', '.join(hit[:4])}{' …' if len(hit) > 4 else ''}",
            where=where, fix="move the spawn pose onto free floor, or move the obstacle")], metrics)
    if turn < 0:
        return Outcome([Finding(
            "spawn-clear", "warning",
            f"{nearest} is {clearance:.3f} m from the robot: too close for it to turn in place "
            f"(its corners sweep {body.turn_radius:.3f} m round its centre)",
            where=where, fix=f"keep the spawn at least {body.turn_radius:.2f} m from walls and obstacles")],
            metrics)
    return Outcome([], metrics)


# ---------------------------------------------------------------------------------------------- sdformat

SDFORMAT_ABSENT = "libsdformat is not installed"
_MISSING_INCLUDE = re.compile(r"^Unable to find uri\[(?P<uri>.*)\]$")
_SHARED_NAME = re.compile(r"^Non-unique names detected in <(?P<tag>\w+) name='(?P<name>[^']*)'")


def check_sdformat(world_file: Path, model_paths=(), shown_as: str | None = None) -> Outcome | None:
    """libsdformat's own check of ``world_file`` (:func:`worldgen.check.sdformat.sdformat_check`; ``model://`` through
    ``model_paths``, GAZEBO_MODEL_PATH and stand-ins for Gazebo's ground_plane and sun), or None when the library
    is not installed. Each distinct complaint is a finding with the file, line and element it names; the path of
    ``world_file`` is written as ``shown_as`` (a spec's world is checked from a temporary file).

    Two complaints are warnings, as Gazebo Classic loads such a world all the same: an include it cannot find
    (the rest of the world loads; the parse check says the same) and names shared by different kinds of children
    (a collision and a visual called alike, which libsdformat 12 refuses as SDF 1.7 does but Gazebo 11 accepts).
    """
    checked = sdformat_check(world_file, model_paths=model_paths)
    if checked is None:
        return None
    valid, text = checked
    if shown_as is not None:
        for form in dict.fromkeys((str(Path(world_file).resolve()), str(world_file))):
            text = text.replace(form, shown_as)
    findings = [_sdformat_finding(m) for m in messages(text)]
    if not valid and not findings:
        findings.append(Finding("sdformat", "error", "libsdformat finds the file invalid but does not say why",
                                where=shown_as or str(world_file), fix=_SDFORMAT_FIX))
    return Outcome(findings, {"sdformat_valid": valid})


_SDFORMAT_FIX = "fix what libsdformat names: Gazebo loads worlds through this library"


def _sdformat_finding(message) -> Finding:
    missing = _MISSING_INCLUDE.match(message.text)
    if missing:
        return Finding("sdformat", "warning", message.text, where=message.where,
                       fix="put the folder holding that model on --model-path or GAZEBO_MODEL_PATH; what the "
                           "include holds was not checked" if missing.group("uri").startswith("model://") else
                           "libsdformat does not download models: what the include holds was not checked")
    shared = _SHARED_NAME.match(message.text)
    if shared:
        return Finding("sdformat", "warning", message.text, where=message.where or f"{shared['tag']} "
                       f"{shared['name']}", fix="give each child of that element a name of its own (for example "
                       "NAME_collision and NAME_visual): SDF 1.7 and libsdformat 12 require it, Gazebo 11 does not")
    return Finding("sdformat", message.severity, message.text, where=message.where, fix=_SDFORMAT_FIX)


# ------------------------------------------------------------------------------------------ simulated checks

def sim_findings(numbers: SimNumbers | dict, no_hit: str, ground: float = 0.0, floor: str | None = None) -> Outcome:
    """Judge what :func:`worldgen.check.sim_job.sim_numbers` measured (parts that did not run are skipped; a
    dict, as the child process sends it, is parsed once into the record here). ``no_hit`` is what a beam that
    hits nothing reads ("inf" or "zero"); ``ground`` is the floor's height at the spawn and ``floor`` the floor
    slab's label, if any: standing on it is no touching."""
    if isinstance(numbers, dict):
        numbers = SimNumbers.from_dict(numbers)
    if floor is not None:
        numbers = _off_the_floor(numbers, floor)
    findings: list[Finding] = []
    metrics: dict = {}
    if numbers.settle is not None:
        findings += _settle_findings(numbers.settle, ground, metrics)
    scan = numbers.lidar
    if scan is not None:
        metrics.update(lidar_beams=scan.beams, lidar_no_hit_beams=scan.no_hit, lidar_no_hit_value=no_hit,
                       lidar_no_hit_reading=scan.no_hit_reading, lidar_nearest_m=scan.nearest,
                       lidar_nearest_bearing_deg=scan.nearest_bearing_deg, lidar_farthest_m=scan.farthest)
        metrics["lidar_front_no_hit"] = scan.front_no_hit
        finding = lidar_no_hit_finding(scan, no_hit)
        if finding is not None:
            findings.append(finding)
    spin = numbers.spin
    if spin is not None:
        metrics.update(spin_drift_m=spin.drift, spin_turned_rad=spin.turned, spin_touched=list(spin.touched))
        if spin.touched:
            findings.append(Finding("spin", "error", f"spinning in place the robot touched {', '.join(spin.touched)}",
                                    where=_contacts_text(spin.contact_points),
                                    fix="move the spawn away from walls and obstacles"))
        elif spin.drift > SPIN_DRIFT_LIMIT:
            findings.append(Finding("spin", "error",
                                    f"spinning in place the robot drifted {spin.drift * 100:.1f} cm "
                                    f"(more than {SPIN_DRIFT_LIMIT * 100:.0f} cm)",
                                    fix="spawn it on flat floor clear of obstacles"))
    if numbers.stop is not None:
        findings += _stop_findings(numbers.stop, metrics)
    for name, message in numbers.failed.items():
        findings.append(Finding(name, "error", message))
    return Outcome(findings, metrics)


def _off_the_floor(numbers: SimNumbers, floor: str) -> SimNumbers:
    """``numbers`` without the touches of the floor slab the robot stands on."""
    def clean(part):
        if part is None:
            return None
        points = tuple(c for c in part.contact_points if c.shape != floor)
        if hasattr(part, "touched"):
            return replace(part, touched=tuple(t for t in part.touched if t != floor), contact_points=points)
        return replace(part, contact_points=points)

    return replace(numbers, settle=clean(numbers.settle), spin=clean(numbers.spin), stop=clean(numbers.stop))


def _settle_findings(settle: Settled, ground: float, metrics: dict) -> list[Finding]:
    metrics.update(settle_tilt_deg=settle.tilt_deg, settle_height_m=settle.z, settle_moved_m=settle.moved)
    if settle.tilt_deg > TILT_LIMIT:
        return [Finding("settle", "error", f"after {settle.time:.1f} s the robot is tipped {settle.tilt_deg:.0f}°",
                        where=_contacts_text(settle.contact_points), fix="spawn it on flat, free floor")]
    if abs(settle.z - ground) > GROUND_LIMIT:
        fell = settle.z < ground
        return [Finding(
            "settle", "error",
            f"after {settle.time:.1f} s the robot is {settle.z - ground:+.3f} m from the floor "
            + ("(it fell through: there is no ground under it)" if fell else "(it rests on something)"),
            where=_contacts_text(settle.contact_points),
            fix="give the world a ground plane" if fell else "spawn it on free floor, clear of obstacles")]
    return []


def _stop_findings(stop: Stopped, metrics: dict) -> list[Finding]:
    metrics.update(stop_distance_m=stop.distance, stop_touched=list(stop.touched), stop_time_s=stop.time,
                   stop_target_m=STOP_TARGET, stop_heading_deg=stop.heading_deg)
    if stop.no_wall:
        return [Finding("stop-at-wall", "info",
                        f"no wall within {stop.range:g} m in any direction: stop at wall was not tried")]
    if stop.touched:
        return [Finding("stop-at-wall", "error",
                        f"driving toward the wall the robot touched {', '.join(stop.touched)} before stopping",
                        where=_contacts_text(stop.contact_points),
                        fix="an obstacle below the LiDAR plane is in the way, or the wall is too close to brake; "
                            "clear the path or move the spawn")]
    if stop.distance is None or abs(stop.distance - STOP_TARGET) > STOP_TOLERANCE:
        ended = "with no wall in range ahead" if stop.distance is None else f"{stop.distance:.2f} m from the wall"
        return [Finding("stop-at-wall", "warning",
                        f"stop at wall ended {ended} instead of {STOP_TARGET} m from it after {stop.time or 0:.1f} s",
                        fix="check the floor ahead of the spawn is flat and free")]
    return []


NO_HIT_SHARE = 0.5   # a warning when at least this share of the beams see nothing (else one info line)
NO_HIT_MEANING = ("a beam that hits nothing reads inf in Gazebo but 0 on the real robot (LDS-01 driver): code must "
                  "treat both as 'nothing seen', never 0 as a wall right ahead")


def lidar_no_hit_finding(scan: Scanned, no_hit: str) -> Finding | None:
    """What beams that hit nothing mean for the student's code, said once: a warning when the beams straight ahead
    or at least :data:`NO_HIT_SHARE` of them see nothing from the spawn (what a stop-at-wall node reads first),
    a short info line when only some far corners are out of range (any room wider than 3.5 m has those), else
    None."""
    missed, beams = scan.no_hit, scan.beams
    if not missed:
        return None
    reads = "inf" if no_hit == "inf" else "0"
    within = f"within {scan.range_max:g} m"
    if missed == beams:
        what = f"all {beams} beams see nothing {within} and read {reads}"
    else:
        what = f"{missed} of {beams} beams see nothing {within} and read {reads}"
    if scan.front_no_hit or missed >= NO_HIT_SHARE * beams:
        ahead = " (straight ahead too)" if scan.front_no_hit and missed != beams else ""
        return Finding("lidar", "warning", f"{what}{ahead}: {NO_HIT_MEANING}",
                       fix="handle both readings in code, or spawn the robot within 3.5 m of a wall ahead")
    return Finding("lidar", "info", f"{what}: only the farthest parts of the room are out of range")


def _contacts_text(points) -> str | None:
    return "; ".join(f"{c.link} touched {c.shape} at t = {c.time:.1f} s" for c in points) or None
