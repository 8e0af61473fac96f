"""Whether an interpreter can import a module (rospy, rclpy), learnt once and kept on disk.

Finding the Python that runs students' nodes asks each candidate interpreter to ``import rospy`` (or ``rclpy``): a
process start and the import, 0.1 to 0.5 s, on every ``worldgen run``. The answer only changes when the interpreter
or the module does, so a yes is kept in worldgen's cache folder (:func:`worldgen.core.resources.cache_dir`,
``interpreters.json``) under the interpreter's path, its real file's size and modification time, and the
``PYTHONPATH`` and ``PYTHONHOME`` it ran with; with it, the module's file and that file's size and modification
time, checked before the yes is used (an uninstalled or upgraded module asks again). A no is never kept:
installing the package must help at once.

The child leaves with ``os._exit`` once it has answered, skipping the module's own exit handlers (rospy's sleep a
tenth of a second at exit). A cache folder that cannot be read or written is no error: the question is asked again.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from pathlib import Path

from ..core.resources import cache_dir

FILE = "interpreters.json"
PROBE = ("import os, sys\n"
         "import {module}\n"
         "sys.stdout.write(os.path.realpath(getattr({module}, '__file__', None) or ''))\n"
         "sys.stdout.flush()\n"
         "os._exit(0)\n")


def _stamp(path: str) -> list[int] | None:
    try:
        info = os.stat(path)
    except OSError:
        return None
    return [info.st_mtime_ns, info.st_size]


def _key(python: str, module: str, env: dict[str, str]) -> str | None:
    """The entry's name: the interpreter as named (a venv's ``bin/python`` is a link to the system's, with other
    packages), the file it runs and that file's stamp, and what else decides its ``sys.path``."""
    real = os.path.realpath(python)
    stamp = _stamp(real)
    if stamp is None:
        return None
    return json.dumps([module, os.path.abspath(python), real, stamp, env.get("PYTHONPATH", ""),
                       env.get("PYTHONHOME", "")])


def _load(folder: Path) -> dict:
    try:
        data = json.loads((folder / FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def _store(folder: Path, key: str, value: dict) -> None:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        entries = _load(folder)
        entries[key] = value
        handle, tmp = tempfile.mkstemp(prefix=".interpreters.", dir=folder)
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            json.dump(entries, out)
        os.replace(tmp, folder / FILE)
    except OSError:
        pass


def imports(python: str, module: str, timeout: float = 60.0, env: dict[str, str] | None = None) -> bool:
    """Whether ``python`` imports ``module`` (a top-level name) in ``env`` (default: this process's environment):
    the kept answer while nothing it depends on changed, else asked of a child process (see the module
    docstring)."""
    env = dict(os.environ if env is None else env)
    key = _key(python, module, env)
    folder = cache_dir()
    if key is not None:
        kept = _load(folder).get(key)
        if isinstance(kept, dict) and kept.get("file") and _stamp(kept["file"]) == kept.get("stamp"):
            return True
    try:
        proc = subprocess.run([python, "-c", PROBE.format(module=module)], capture_output=True, timeout=timeout,
                              env=env)
    except (OSError, subprocess.SubprocessError):
        return False
    if proc.returncode != 0:
        return False
    where = proc.stdout.decode("utf-8", "replace").strip()
    if key is not None and where and _stamp(where) is not None:
        _store(folder, key, {"file": where, "stamp": _stamp(where)})
    return True
