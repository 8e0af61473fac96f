"""Where the system's ROS 1 Python is: worldgen may live in a venv or a pipx environment, while rospy comes from
Debian (``python3-rospy``, in ``/usr/lib/python3/dist-packages``) or from ROS's own packages (``/opt/ros/noetic``,
put on ``PYTHONPATH`` by ``setup.bash``).

:func:`import_rospy` makes ``import rospy`` work in this process (appending the folder that holds it to
``sys.path``, after the environment's own packages), :func:`ros_python_path` lists those folders for a child
process, and :func:`node_python` is the interpreter that runs students' nodes (the one that has rospy, as
``rosrun`` would: ``/usr/bin/python3`` normally). When rospy is nowhere, :func:`missing_rospy` says which
package to install.
"""

from __future__ import annotations

import functools
import os
import subprocess
import sys
from pathlib import Path

from ..core.errors import InputError

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


@functools.lru_cache(maxsize=None)
def _imports_rospy(python: str) -> bool:
    try:
        return subprocess.run([python, "-c", "import rospy"], capture_output=True, timeout=30).returncode == 0
    except (OSError, subprocess.SubprocessError):
        return False


def node_python() -> str:
    """The interpreter for students' nodes: ``$WORLDGEN_ROS_PYTHON``, else the system's python3 when it imports
    rospy, else this one; InputError (the package to install) when none can."""
    chosen = os.environ.get(ENV_PYTHON)
    candidates = [chosen] if chosen else [SYSTEM_PYTHON, sys.executable]
    for python in candidates:
        if python and os.access(python, os.X_OK) and _imports_rospy(python):
            return python
    raise missing_rospy([p for p in candidates if p])
