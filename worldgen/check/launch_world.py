"""Why a launch file's world cannot be found, said once, with what to add.

A lab package handed in unchanged starts the class's world from another course package
(``$(find class_meeting_02_custom_gazebo_world)/worlds/enclosed_room.world``). When that package is nowhere — not in
the lab's workspace, not in the folder graded, not on ``ROS_PACKAGE_PATH`` — the read of the launch file says the
package is missing wherever it is used, and the launch file's row says its world cannot be found: one cause.
:func:`world_not_found` makes that one error finding, naming the package and where to put it (and, for one of the
course's own packages, the command that writes it); any other reason keeps the plain message.
"""

from __future__ import annotations

from pathlib import Path
from typing import List

from ..core.findings import Finding
from ..launch.reader import is_python_launch, package_index
from ..packages.course_names import SHARED_WORLD_PACKAGES
BUILD_FIX = "build it (worldgen build SPEC --package DIR) or fix the world's path in the launch file"
PLAIN_FIX = ("make the world it passes to Gazebo (world_name; world or gz_args in a launch.py) an existing world file "
             "(is the package on ROS_PACKAGE_PATH or in this workspace?), or validate the world itself with "
             "--launch THIS_FILE")


def world_not_found(info, path: Path, findings: List[Finding], graded: bool, search=None) -> List[Finding]:
    """``findings`` (the read's) with the error of a world that cannot be found: when a package that is nowhere
    is the cause (``info.package``), the read's findings of that package are folded into it, and a package that
    is there under a name a letter or two off is named (``search``: where ``$(find)`` looked after the launch
    file's workspace, None for ROS_PACKAGE_PATH). ``graded``: the launch file is in a folder given to grade,
    whose packages held once were searched too."""
    ref = info.world_ref or "(none)"
    package = info.package
    missing = f"package {package!r} not found" if package else None
    same = [f for f in findings if missing and f.check == "launch-find" and missing in f.message]
    if info.world_path is not None:   # resolved, but no file there
        return findings + [Finding("launch", "error", f"the world this launch file starts cannot be found: "
                                   f"{info.world_path} does not exist", where=str(path), fix=BUILD_FIX)]
    if not same:
        return findings + [Finding("launch", "error", f"the world this launch file starts cannot be found: {ref}",
                                   where=str(path), fix=PLAIN_FIX)]
    ros2 = is_python_launch(path)
    looked = ["this package's workspace"] + (["the folder graded"] if graded else []) + ["ROS_PACKAGE_PATH"] + \
        (["AMENT_PREFIX_PATH"] if ros2 else [])
    message = (f"the world this launch file starts cannot be found: {ref} (the package {package} is not in "
               f"{', '.join(looked[:-1])} or {looked[-1]})")
    near = package_index(path, search).misspelt(package)
    fix = (f"write $(find {near}) (the package {near} is there)" if near else _where_to_put(package, graded, ros2))
    return [f for f in findings if f not in same] + [
        Finding("launch", "error", message + (f"; did you mean {near!r}?" if near else ""), where=same[0].where,
                fix=fix)]


def _where_to_put(package: str, graded: bool, ros2: bool) -> str:
    """Where the missing package can go so that the world is found."""
    places = ([f"put {package} in the folder graded, beside the submissions (one copy serves them all)"] if graded
              else [f"put {package} in this package's workspace"])
    places.append("put the folder holding it on ROS_PACKAGE_PATH")
    if ros2:
        places.append("source the ROS 2 install that has it (AMENT_PREFIX_PATH)")
    fix = ", or ".join(places)
    if package in SHARED_WORLD_PACKAGES:
        stack = " --ros humble|jazzy" if ros2 else ""
        fix += (f"; it is one of the course's packages: 'worldgen course -w DIR{stack}' writes it to "
                f"DIR/src/intro_robo/{package}")
    return fix
