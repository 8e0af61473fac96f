"""The self-contained 3D page: one HTML file holding three.js (vendored, see :mod:`.vendor`), the page's own script
and the data it draws (:mod:`.scene_data`, and for a run :mod:`.replay`). Opening it loads nothing from anywhere:
every script is inlined as text and linked through ``blob:`` URLs by a small loader (``templates/view/boot.js``).

The pages of a report folder (:mod:`.grades`) share one copy of three.js instead: :func:`library_script`, a plain
script beside them holding the same texts, which each page loads by its file name (``render_page(...,
library="three.js")``; the page's security policy lets it load scripts of its own origin, which from ``file://`` is
a file, and nothing else), so that 40 pages carry 0.9 MB of three.js once, not 40 times.

The same inputs give the same bytes: the data is JSON of rounded values in a fixed order, and nothing in the page
depends on the time or the machine it was written on.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Sequence, Tuple

from ..core.findings import Finding
from ..check.sources import WorldSource
from ..core.errors import InputError, WorldgenError
from ..core.resources import render_template, templates_dir
from .replay import drive_replay
from .scene_data import ShownWorld, read_source, static_models, world_data, world_title
from .vendor import THREE_VERSION, modules

LIBRARIES = ("three", "BufferGeometryUtils", "GLTFLoader", "OrbitControls")
_CLOSERS = re.compile(r"</script|<!--", re.IGNORECASE)


def _script_text(name: str, text: str) -> str:
    """``text`` to inline in a ``<script>`` element, refused if it could end the element early."""
    found = _CLOSERS.search(text)
    if found:
        raise WorldgenError(f"{name} cannot be inlined in a page: it holds {found.group(0)!r}",
                            hint="please report this to the worldgen developers")
    return text


def require_three() -> None:
    """Fail now (WorldgenError, one line) when this installation has no three.js: before a run whose page could
    not be written after it."""
    modules()


def _csp_hash(script: str) -> str:
    """The Content Security Policy source that lets exactly this inline script run (the page's loader)."""
    import base64
    import hashlib

    return "sha256-" + base64.b64encode(hashlib.sha256(script.encode("utf-8")).digest()).decode("ascii")


def data_json(data: dict) -> str:
    """``data`` as JSON that is safe inside a script element: every ``<``, ``>`` and ``&`` escaped."""
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _template_text(name: str) -> str:
    return (templates_dir() / "view" / name).read_text(encoding="utf-8")


def finding_items(findings: Sequence[Finding]) -> list[dict]:
    """Findings as the page lists them, errors first."""
    order = {"error": 0, "warning": 1, "info": 2}
    ranked = sorted(enumerate(findings), key=lambda item: (order.get(item[1].severity, 3), item[0]))
    out = []
    for _, f in ranked:
        where = f"{f.where}:{f.line}" if getattr(f, "where", None) and getattr(f, "line", None) else ""
        message = f"{f.message} ({where})" if where else f.message
        out.append({"severity": f.severity, "check": f.check, "message": message, "fix": f.fix or ""})
    return out


@dataclass(frozen=True)
class Panel:
    """What a page says beside the world: its title, the verdict, metrics and findings; ``back``: a relative
    link to the class's index (a page of a ``--html DIR`` report)."""

    title: str
    subtitle: str = ""
    findings: Sequence[Finding] = ()
    verdict: Optional[str] = None
    verdict_text: str = ""
    metrics: Sequence[Tuple[str, str]] = ()
    back: Optional[str] = None


def render_page(data: dict, panel: Panel, library: Optional[str] = None) -> bytes:
    """The HTML page for ``data`` (a world's, with ``replay`` for a run), ``panel`` beside it; three.js inlined, or
    with ``library`` (a file name beside the page, written by :func:`library_script`) loaded from there."""
    from markupsafe import Markup

    libraries = modules()
    boot = _script_text("boot.js", _template_text("boot.js"))
    code = [] if library else [(name, Markup(_script_text(name, libraries[name]))) for name in LIBRARIES]
    replay = data.get("replay")
    html = render_template(
        "view/page.html.j2", title=panel.title, subtitle=panel.subtitle, css=Markup(_template_text("page.css")),
        data_json=Markup(data_json(data)), libraries=code, library=library,
        app=Markup(_script_text("page.js", _template_text("page.js"))),
        boot=Markup(boot), boot_hash=_csp_hash(f"\n{boot}\n"), three_version=THREE_VERSION,
        three_license=Markup(_script_text("LICENSE", libraries["LICENSE"])), replay=replay is not None,
        replay_duration=(replay["t"][-1] if replay and replay["t"] else 0), rays="rays" in data or replay is not None,
        findings=finding_items(panel.findings), verdict=panel.verdict, verdict_text=panel.verdict_text,
        metrics=list(panel.metrics), back=panel.back)
    return html.encode("utf-8")


def library_script() -> bytes:
    """The shared three.js of a report folder's pages: a plain (not module) script defining
    ``window.worldgenLibraries``, the texts the page's loader links as it links inlined ones, with three.js's
    licence at its top. A plain script, because chromium refuses a module script from ``file://`` (its origin is
    opaque); the texts as JSON in ASCII (escapes for anything else), so that they read the same in any charset."""
    libraries = modules()
    licence = libraries["LICENSE"].strip()
    if "*/" in licence:
        raise WorldgenError("three.js's LICENSE cannot go in a comment: it holds */",
                            hint="please report this to the worldgen developers")
    texts = json.dumps({name: libraries[name] for name in LIBRARIES}, ensure_ascii=True, separators=(",", ":"))
    return (f"/* three.js {THREE_VERSION} with its OrbitControls, GLTFLoader and BufferGeometryUtils, for the "
            f"worldgen pages beside this file.\n\n{licence}\n*/\nwindow.worldgenLibraries = {texts};\n"
            ).encode("utf-8")


def world_page(path: str | Path, *, spawn: tuple[float, float, float] | None = None, robot: str | None = None,
               lidar: bool = False, model_paths: Sequence[str | Path] = ()) -> bytes:
    """The page of a world file, a spec or a launch file: the world as Gazebo draws it, the robot at its spawn
    pose (``spawn``/``robot`` override what the input says), LiDAR rays from there with ``lidar``."""
    import dataclasses

    source = read_source(path, model_paths)
    if spawn is not None:
        source = dataclasses.replace(source, spawn=tuple(spawn))
    if robot is not None:
        source = dataclasses.replace(source, robot=robot)
    rays = None
    if lidar:
        if source.spawn is None:
            raise InputError("--lidar needs a spawn pose", hint="give --spawn X,Y[,YAW] or a robot: in the spec")
        rays = scan_rays(source, model_paths)
    data = world_data(source, rays)
    return render_page(data, Panel(source.title, source.subtitle, findings=_scene_findings(source.scene),
                                   metrics=world_facts(data)))


def scan_rays(source, model_paths=(), timeout: float = 120.0) -> list:
    """One noiseless LiDAR scan from ``source``'s spawn pose (``preview``'s job, in a simulator child process)."""
    from .preview import Picture, Spawn, lidar_rays

    spawn = Spawn(*source.spawn, model=source.robot)
    picture = Picture(source.scene, source.title, world=source.world)
    return lidar_rays(picture, spawn, model_paths, timeout)


def world_facts(data: dict) -> list[tuple[str, str]]:
    """What the side panel says of a world: its size, what it holds, the robot and where it spawns."""
    x0, y0, x1, y1 = data["bounds"]
    groups = [item["g"] for item in data["items"]]
    facts = [("size", f"{x1 - x0:.2f} × {y1 - y0:.2f} m")]
    for group, label in (("wall", "wall shapes"), ("obstacle", "obstacle shapes"), ("marking", "floor-marking pieces")):
        if group in groups:
            facts.append((label, str(groups.count(group))))
    for kind in ("door", "window"):
        count = sum(o["type"] == kind for o in data["openings"])
        if count:
            facts.append((f"{kind}s", str(count)))
    facts.append(("rooms", str(len(data["plan"]["rooms"]))))
    robot = data["robot"]
    if robot["spawn"] is not None:
        x, y, yaw = robot["spawn"]
        facts.append((robot["model"], f"({_fixed(x, 2)}, {_fixed(y, 2)}), yaw {_fixed(math.degrees(yaw), 0)}°"))
    return facts


def _fixed(value: float, digits: int) -> str:
    """``value`` with ``digits`` decimals, and never a negative zero (-0.001 reads 0.00, not -0.00)."""
    return f"{round(value, digits) + 0.0:.{digits}f}"


def _scene_findings(scene) -> list[Finding]:
    """What the world reader said, but its infos."""
    return [f for f in scene.findings if f.severity != "info"]


def world_source(path: str | Path, scene, spawn=None, robot: str = "burger"):
    """The page's view of a world already read (by ``run`` or ``validate``): a spec's rooms and openings are
    taken from the spec again (its building is cheap to rebuild), anything else from ``scene`` itself."""
    import dataclasses

    from ..check.validate import input_kind

    path = Path(path)
    if path.is_file() and input_kind(path) == "spec":
        source = read_source(path)
    else:
        source = ShownWorld(scene, world_title(scene, path), path.name, world=WorldSource(path),
                            walls=static_models(scene))
    return dataclasses.replace(source, spawn=tuple(spawn) if spawn is not None else source.spawn, robot=robot)


def replay_page(source, replay: dict, panel: Panel, library: Optional[str] = None) -> bytes:
    """The page of a run: the world of ``source`` (:func:`world_source`), the robot replayed along ``replay``
    (:mod:`.replay`), ``panel`` (the verdict, metrics and findings) beside it; ``library``: as
    :func:`render_page` takes it."""
    data = world_data(source)
    data["replay"] = replay
    data["robot"]["spawn"] = [replay["x"][0], replay["y"][0], replay["yaw"][0]] if replay["t"] else \
        data["robot"]["spawn"]
    return render_page(data, panel, library)


def drive_page(world: str | Path, result: dict, model_paths: Sequence[str | Path] = (),
               failures: Sequence[str] = ()) -> bytes:
    """The page of ``worldgen drive``'s first run (:func:`worldgen.sim.exercise.drive_exercise`'s result, with
    its scans recorded): the world, the robot replayed, the numbers the text report gives and why it failed."""
    import dataclasses

    source = dataclasses.replace(read_source(world, model_paths), spawn=tuple(result["spawn"]), robot=result["robot"])
    run = result["runs"][0]
    if result["behaviour"] == "spin":
        metrics = [("turned", f"{math.degrees(run['turned']):.0f}°"),
                   ("drift at the end", f"{_fixed(run['drift'] * 1000, 1)} mm"),
                   ("largest drift", f"{_fixed(run['max_drift'] * 1000, 1)} mm")]
    else:
        metrics = [(label, "–" if run.get(key) is None else f"{_fixed(run[key], 3)} {unit}".strip())
                   for key, label, unit in (("final_distance", "final distance", "m"),
                                            ("steady_state_error", "error", "m"), ("min_distance", "closest", "m"),
                                            ("overshoot", "overshoot", "m"), ("settling_time", "settling time", "s"))]
        metrics.insert(0, ("gains", f"kp={run['kp']:g} ki={run['ki']:g} kd={run['kd']:g}"))
    metrics.append(("contacts", str(len(run["contacts"]))))
    verdict = "ok" if run["ok"] else "FAIL"
    findings = [Finding("drive", "error", text) for text in failures]
    return replay_page(source, drive_replay(result), Panel(
        f"{result['behaviour']} in {source.title}", source.subtitle, findings=findings, verdict=verdict,
        verdict_text=f"{result['behaviour']}: {'pass' if run['ok'] else 'fail'}", metrics=metrics))
