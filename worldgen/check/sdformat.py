"""libsdformat's own check of a world or model file, where the library is installed.

libsdformat exports ``cmdCheck(path)``, the function behind ``ign sdf -k``: it parses the file as Gazebo would,
converts it to the library's newest SDF version, checks names, poses and frames, prints what is wrong to stderr
and returns 0 or -1. It is called through ctypes in a child process, so that its messages (written by C code
straight to the file descriptors) can be captured and a crash in the library cannot take the caller down.

``model://`` includes are resolved through ``SDF_PATH``: the child gets the given model folders, then
``GAZEBO_MODEL_PATH``, ``SDF_PATH`` and Gazebo Sim's resource paths (as the world reader searches them), then
stand-ins for Gazebo's stock ``ground_plane`` and ``sun`` (which a
Gazebo install carries but libsdformat alone does not), so that a stock world does not fail for that alone.
:func:`messages` turns what the library printed into one :class:`Message` per distinct complaint.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

LIBRARIES = ("libsdformat12.so.12", "libsdformat12.so", "libsdformat13.so.13", "libsdformat14.so.14")
_ABSENT = 3     # the child's exit code when no library with cmdCheck loads
_COLOUR = re.compile(r"\x1b\[[0-9;]*m")

_CHILD = f"""
import ctypes, sys
for name in {LIBRARIES!r}:
    try:
        check = ctypes.CDLL(name).cmdCheck
    except (OSError, AttributeError):
        continue
    check.argtypes = [ctypes.c_char_p]
    check.restype = ctypes.c_int
    sys.exit(0 if check(sys.argv[1].encode()) == 0 else 1)
sys.exit({_ABSENT})
"""

_CONFIG = """<?xml version="1.0"?>
<model>
  <name>{name}</name>
  <version>1.0</version>
  <sdf version="1.6">model.sdf</sdf>
  <description>worldgen's stand-in for Gazebo's stock {name} model, for libsdformat's check only</description>
</model>
"""
STOCK_STUBS = {
    "ground_plane": """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="ground_plane">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      </collision>
      <visual name="visual">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      </visual>
    </link>
  </model>
</sdf>
""",
    "sun": """<?xml version="1.0"?>
<sdf version="1.6">
  <light type="directional" name="sun">
    <cast_shadows>true</cast_shadows>
    <pose>0 0 10 0 0 0</pose>
    <diffuse>0.8 0.8 0.8 1</diffuse>
    <specular>0.2 0.2 0.2 1</specular>
    <direction>-0.5 0.1 -0.9</direction>
  </light>
</sdf>
""",
}


def write_stock_stubs(folder: Path) -> Path:
    """Write minimal ``ground_plane`` and ``sun`` models (model.config + model.sdf) into ``folder``; return it."""
    for name, sdf in STOCK_STUBS.items():
        (folder / name).mkdir(parents=True, exist_ok=True)
        (folder / name / "model.config").write_text(_CONFIG.format(name=name), encoding="utf-8")
        (folder / name / "model.sdf").write_text(sdf, encoding="utf-8")
    return folder


def sdf_path(model_paths=(), stubs: Path | None = None, env=None) -> str:
    """The child's ``SDF_PATH``: ``model_paths``, ``GAZEBO_MODEL_PATH``, ``SDF_PATH``, ``GZ_SIM_RESOURCE_PATH``,
    ``IGN_GAZEBO_RESOURCE_PATH``, then ``stubs`` (last, so that a real ground_plane or sun on a model path wins)."""
    from ..sdf.resolve import MODEL_PATH_VARIABLES

    env = os.environ if env is None else env
    folders = [os.fspath(Path(p).resolve()) for p in model_paths]
    for name in MODEL_PATH_VARIABLES:
        folders += [p for p in env.get(name, "").split(os.pathsep) if p.strip()]
    if stubs is not None:
        folders.append(os.fspath(stubs))
    return os.pathsep.join(dict.fromkeys(folders))


def sdformat_check(path: str | Path, *, model_paths=(), stubs: bool = True, timeout: float = 300.0
                   ) -> tuple[bool, str] | None:
    """``(valid, messages)`` from libsdformat's check of ``path``, or None when the library is not installed.

    ``model_paths`` are searched first for ``model://`` includes (see :func:`sdf_path`); ``stubs`` adds the
    stand-ins for Gazebo's stock models. ``messages`` is what the library printed (stdout and stderr, without
    colour codes). A crash or a timeout counts as not valid, with the reason in ``messages``.
    """
    cmd = [sys.executable, "-c", _CHILD, os.fspath(Path(path).resolve())]
    with tempfile.TemporaryDirectory(prefix="worldgen_sdformat_") as tmp:
        env = dict(os.environ, SDF_PATH=sdf_path(model_paths, write_stock_stubs(Path(tmp)) if stubs else None))
        try:
            done = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout, env=env)
        except subprocess.TimeoutExpired:
            return False, f"libsdformat did not finish checking {path} within {timeout:g} s"
    if done.returncode == _ABSENT:
        return None
    messages = _COLOUR.sub("", "\n".join(p.strip() for p in (done.stdout, done.stderr) if p.strip()))
    if done.returncode < 0:
        return False, f"libsdformat crashed (signal {-done.returncode}) checking {path}\n{messages}".strip()
    return done.returncode == 0, messages


# ---------------------------------------------------------------------------------------------- messages

@dataclass(frozen=True)
class Message:
    """One complaint of libsdformat's: ``severity`` (error or warning), its text, and where it points when it
    says (``file``, ``line``, and ``element``, the element path shortened: ``world[default]/model[m]/link[l]``)."""

    severity: str
    text: str
    file: str | None = None
    line: int | None = None
    element: str | None = None

    @property
    def where(self) -> str | None:
        place = f"{self.file}:{self.line}" if self.file and self.line else self.file
        if self.element:
            return f"{place} ({self.element})" if place else self.element
        return place


MAX_TEXT = 300   # characters of one message kept (some messages dump a whole element's XML)
_PREFIX = re.compile(r"^(?:Error Code \d+:|Error|Warning|ERROR)\s*(?:\[[\w.]+:\d+\])?\s*:?\s*")
_LOCATION = re.compile(r"^\[(?P<where>.*?):L(?P<line>\d+)\]:\s*")
_NAME = re.compile(r'\[@name="([^"]*)"\]')
_NOISE = ("findFile(), but the callback is empty",      # said once more for each include it cannot find
          "Could not find the 'robot' element",          # the URDF parser's try after the SDF parser gave up
          "urdf_parser")
_CASCADE = ("Failed to load a world", "Unable to read file", "Error reading element <sdf>")
_READING = re.compile(r"^Error reading element <[^>]*>$")


def messages(text: str) -> list[Message]:
    """libsdformat's output as distinct messages, in order, trimmed.

    A message is a line and the indented (or XML) lines under it, of which only the first is kept. Trimmed away:
    the URDF parser's attempt after the SDF parser gave up, the repeated notes about a missing find-file callback,
    and the "Error reading element <parent>" cascade each error sets off up to ``<sdf>``. A bare cause
    ("Unable to set value [1 2 ] for key[size]") takes the file, line and element of the cascade's first step.
    """
    found: list[Message] = []
    cause: Message | None = None
    for head in _heads(text):
        if head.strip() == "Valid." or any(n in head for n in _NOISE):
            continue
        message = _message(head)
        if _READING.match(message.text) and message.element is not None:
            if any(_within(m.element, message.element) for m in found):
                continue            # a parent of an element already reported
            if cause is not None:   # the cause said just before, placed where the cascade starts
                found[found.index(cause)] = Message(cause.severity, cause.text, message.file, message.line,
                                                    message.element)
                cause = None
                continue
        cause = message if message.severity == "error" and message.element is None else None
        if message not in found:
            found.append(message)
    generic = [m.severity == "error" and m.text.startswith(_CASCADE) for m in found]
    if any(m.severity == "error" and not g for m, g in zip(found, generic)):
        found = [m for m, g in zip(found, generic) if not g]   # a cascade's generic end: something better was said
    return _place_duplicates(found)


_EXISTS = re.compile(r"^(?P<kind>\w+) with name\[(?P<name>.*)\] already exists\.?$")
_NON_UNIQUE = re.compile(r"^Non-unique name\[(?P<name>.*)\] detected \d+ times in XML children of "
                         r"(?P<kind>\w+) with name\[(?P<parent>.*)\]\.?$")


def _place_duplicates(found: list[Message]) -> list[Message]:
    """"link with name[l] already exists" says not where; the warning "Non-unique name[l] detected 2 times in XML
    children of model with name[m]" does: the error takes ``model m`` as its element, the warning goes."""
    parents = {}
    for m in found:
        warned = _NON_UNIQUE.match(m.text) if m.severity == "warning" else None
        if warned:
            parents.setdefault(warned["name"], (m, f"{warned['kind']} {warned['parent']}"))
    used = set()
    placed = []
    for m in found:
        exists = _EXISTS.match(m.text) if m.severity == "error" and m.where is None else None
        if exists and exists["name"] in parents:
            warning, element = parents[exists["name"]]
            used.add(id(warning))
            m = Message(m.severity, m.text, element=element)
        placed.append(m)
    return [m for m in placed if id(m) not in used]


def _within(element: str | None, parent: str) -> bool:
    return element is not None and (element == parent or element.startswith(parent + "/"))


def _heads(text: str) -> list[str]:
    """The first line of each message: lines that start with neither a blank nor ``<`` (an XML dump)."""
    return [line.rstrip() for line in text.splitlines() if line.strip() and not line[0].isspace()
            and not line.startswith("<")]


def _message(line: str) -> Message:
    severity = "warning" if line.startswith("Warning") else "error"
    rest = _PREFIX.sub("", line, count=1)
    file = line_no = element = None
    located = _LOCATION.match(rest)
    if located:
        element, file = _split_location(located.group("where"))
        line_no = int(located.group("line"))
        rest = rest[located.end():]
    rest = re.sub(r"^Msg:\s*", "", rest).strip()
    if len(rest) > MAX_TEXT:
        rest = rest[:MAX_TEXT - 1] + "…"
    return Message(severity, rest, file, line_no, element)


def _split_location(where: str) -> tuple[str | None, str]:
    """``/sdf/world[@name="w"]/…:FILE`` → (``world[w]/…``, FILE); the element path may hold quoted colons."""
    if not where.startswith("/sdf"):
        return None, where
    quoted = False
    for i, char in enumerate(where):
        if char == '"':
            quoted = not quoted
        elif char == ":" and not quoted:
            path, file = where[:i], where[i + 1:]
            return _NAME.sub(r"[\1]", path[len("/sdf/"):]) or None, file
    return _NAME.sub(r"[\1]", where[len("/sdf/"):]) or None, ""
