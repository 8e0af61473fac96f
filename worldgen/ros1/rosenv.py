"""Where the system's ROS 1 Python is: worldgen may live in a venv or a pipx environment, while rospy comes from
Debian (``python3-rospy``, in ``/usr/lib/python3/dist-packages``) or from ROS's own packages (``/opt/ros/noetic``,
put on ``PYTHONPATH`` by ``setup.bash``).

:func:`import_rospy` makes ``import rospy`` work in this process (appending the folder that holds it to
``sys.path``, after the environment's own packages; :func:`find_rospy` the same without the import),
:func:`ros_python_path` lists those folders for a child
process, and :func:`node_python` is the interpreter that runs students' nodes (the one that has rospy, as
``rosrun`` would: ``/usr/bin/python3`` normally). When rospy is nowhere, :func:`missing_rospy` says which
package to install.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import sys
from pathlib import Path

from ..core.errors import InputError
from ..runtime.interpreters import imports

NOETIC = "/opt/ros/noetic/lib/python3/dist-packages"
DEBIAN = "/usr/lib/python3/dist-packages"
SYSTEM_PYTHON = "/usr/bin/python3"
ENV_PYTHON = "WORLDGEN_ROS_PYTHON"   # overrides the interpreter for students' nodes


def _holds_rospy(folder: str) -> bool:
    return (Path(folder) / "rospy" / "__init__.py").is_file()


def ros_python_path(environ=None) -> list[str]:
    """Folders holding rospy, best first: ROS entries of ``PYTHONPATH``, then ``/opt/ros/noetic``'s, then
    Debian's."""
    environ = os.environ if environ is None else environ
    found = []
    for folder in [p for p in environ.get("PYTHONPATH", "").split(os.pathsep) if p] + [NOETIC, DEBIAN]:
        if folder not in found and _holds_rospy(folder):
            found.append(folder)
    return found


def distro_package() -> str:
    """The package that provides rospy on this system: ``ros-noetic-rospy`` where ROS's own apt repository is
    used (Ubuntu with /opt/ros), ``python3-rospy`` on Debian."""
    try:
        release = Path("/etc/os-release").read_text(encoding="utf-8", errors="replace").lower()
    except OSError:
        release = ""
    if Path("/opt/ros").is_dir() or "id=ubuntu" in release:
        return "ros-noetic-rospy"
    return "python3-rospy"


def missing_rospy(tried: list[str] | None = None) -> InputError:
    """rospy is nowhere (``tried``: the Pythons that could not import it, said in the message): the package."""
    package = distro_package()
    where = f"importable by {', '.join(tried)}" if tried else "installed"
    chosen = os.environ.get(ENV_PYTHON)
    if chosen and tried == [chosen]:
        return InputError(f"rospy (ROS 1's Python client) is not importable by {chosen}, the Python {ENV_PYTHON} "
                          "names", hint=f"name a Python that has rospy (/usr/bin/python3 with {package}), or unset "
                                        f"{ENV_PYTHON}")
    return InputError(f"rospy (ROS 1's Python client) is not {where}: install {package}",
                      hint=f"apt install {package}" + (" and source /opt/ros/noetic/setup.bash"
                                                       if package.startswith("ros-") else ""))


def import_rospy():
    """``import rospy`` in this process, finding the system's ROS Python when the environment lacks it;
    InputError naming the package to install when rospy is nowhere."""
    try:
        import rospy
        return rospy
    except ImportError:
        pass
    for folder in ros_python_path():
        if folder not in sys.path:
            sys.path.append(folder)
    try:
        import rospy
        return rospy
    except ImportError:
        raise missing_rospy() from None


def find_rospy() -> None:
    """What :func:`import_rospy` makes sure of, without importing rospy here (a fifth of a second): the system's
    ROS Python folders on ``sys.path`` when the environment lacks rospy, InputError naming the package to install
    when rospy cannot be imported. Whether it can is asked of a child of this interpreter with this ``sys.path``,
    once (kept: :mod:`worldgen.runtime.interpreters`). For the processes that only start rospy nodes."""
    if importlib.util.find_spec("rospy") is None:
        for folder in ros_python_path():
            if folder not in sys.path:
                sys.path.append(folder)
        importlib.invalidate_caches()
    if "rospy" in sys.modules:
        return
    if importlib.util.find_spec("rospy") is None:
        raise missing_rospy()
    extra = [p for p in ros_python_path() if p in sys.path]
    path = os.pathsep.join(p for p in [os.environ.get("PYTHONPATH", "")] + extra if p)
    if not imports(sys.executable, "rospy", timeout=30, env=dict(os.environ, PYTHONPATH=path)):
        raise missing_rospy()


@functools.lru_cache(maxsize=None)
def _imports_rospy(python: str) -> bool:
    """Asked once a process, and kept on disk while the interpreter and rospy stay (:mod:`worldgen.runtime.
    interpreters`)."""
    return imports(python, "rospy", timeout=30)


def node_python() -> str:
    """The interpreter for students' nodes: ``$WORLDGEN_ROS_PYTHON``, else the system's python3 when it imports
    rospy, else this one; InputError (the package to install) when none can."""
    chosen = os.environ.get(ENV_PYTHON)
    candidates = [chosen] if chosen else [SYSTEM_PYTHON, sys.executable]
    for python in candidates:
        if python and os.access(python, os.X_OK) and _imports_rospy(python):
            return python
    raise missing_rospy([p for p in candidates if p])
