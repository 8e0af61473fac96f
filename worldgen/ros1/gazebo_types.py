"""gazebo_msgs for machines without Gazebo: the message and service types of Gazebo's ROS 1 interface
(``/gazebo/model_states``, ``get_model_state``, ``spawn_sdf_model`` …), generated with genpy from our own
``.msg``/``.srv`` text.

Debian has no gazebo_msgs package, and a class machine without Gazebo has none either, so the types that the
simulator's services speak and that students' nodes import (``from gazebo_msgs.srv import GetModelState``) are
written here from the public interface — the same fields, in the same order, so their MD5 sums and wire format
are Gazebo's own — and turned into a Python package by genpy (Debian's ``python3-genpy``, which every rospy
install has) in worldgen's cache folder, once per definition set. Where a real gazebo_msgs is importable (a ROS
Noetic desktop with gazebo_ros), that one is used and nothing is generated.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..core.errors import InputError
from .rosenv import import_rospy

MESSAGES = {
    "ModelState": """\
string model_name
geometry_msgs/Pose pose
geometry_msgs/Twist twist
string reference_frame
""",
    "ModelStates": """\
string[] name
geometry_msgs/Pose[] pose
geometry_msgs/Twist[] twist
""",
    "LinkState": """\
string link_name
geometry_msgs/Pose pose
geometry_msgs/Twist twist
string reference_frame
""",
    "LinkStates": """\
string[] name
geometry_msgs/Pose[] pose
geometry_msgs/Twist[] twist
""",
    "ODEPhysics": """\
bool auto_disable_bodies
uint32 sor_pgs_precon_iters
uint32 sor_pgs_iters
float64 sor_pgs_w
float64 sor_pgs_rms_error_tol
float64 contact_surface_layer
float64 contact_max_correcting_vel
float64 cfm
float64 erp
uint32 max_contacts
""",
}

_STATUS = "bool success\nstring status_message\n"
SERVICES = {
    "GetModelState": "string model_name\nstring relative_entity_name\n---\nHeader header\n"
                     "geometry_msgs/Pose pose\ngeometry_msgs/Twist twist\n" + _STATUS,
    "SetModelState": "gazebo_msgs/ModelState model_state\n---\n" + _STATUS,
    "GetLinkState": "string link_name\nstring reference_frame\n---\ngazebo_msgs/LinkState link_state\n" + _STATUS,
    "SetLinkState": "gazebo_msgs/LinkState link_state\n---\n" + _STATUS,
    "SpawnModel": "string model_name\nstring model_xml\nstring robot_namespace\ngeometry_msgs/Pose initial_pose\n"
                  "string reference_frame\n---\n" + _STATUS,
    "DeleteModel": "string model_name\n---\n" + _STATUS,
    "GetWorldProperties": "---\nfloat64 sim_time\nstring[] model_names\nbool rendering_enabled\n" + _STATUS,
    "GetModelProperties": "string model_name\n---\nstring parent_model_name\nstring canonical_body_name\n"
                          "string[] body_names\nstring[] geom_names\nstring[] joint_names\n"
                          "string[] child_model_names\nbool is_static\n" + _STATUS,
    "GetPhysicsProperties": "---\nfloat64 time_step\nbool pause\nfloat64 max_update_rate\n"
                            "geometry_msgs/Vector3 gravity\ngazebo_msgs/ODEPhysics ode_config\n" + _STATUS,
}
DEPENDENCIES = ("std_msgs", "geometry_msgs")
ENV_CACHE = "WORLDGEN_CACHE"   # where generated types go (default: $XDG_CACHE_HOME/worldgen or ~/.cache/worldgen)


def _digest() -> str:
    text = repr(sorted(MESSAGES.items())) + repr(sorted(SERVICES.items()))
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def cache_root() -> Path:
    if os.environ.get(ENV_CACHE):
        return Path(os.environ[ENV_CACHE])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "worldgen"


def system_has_gazebo_msgs() -> bool:
    """Whether a real gazebo_msgs is importable here (besides ours)."""
    import importlib.util

    try:
        spec = importlib.util.find_spec("gazebo_msgs")
    except (ImportError, ValueError):
        return False
    return spec is not None and "worldgen" not in str(spec.origin or spec.submodule_search_locations)


def _definition_dirs(package: str) -> list[str]:
    """Folders holding ``package``'s ``.msg`` files: ROS_PACKAGE_PATH's packages, /opt/ros/noetic, Debian's
    /usr/share."""
    candidates = [os.path.join(root, package, "msg") for root in os.environ.get("ROS_PACKAGE_PATH", "").split(":")
                  if root]
    candidates += [f"/opt/ros/noetic/share/{package}/msg", f"/usr/share/{package}/msg"]
    return [c for c in candidates if os.path.isfile(os.path.join(c, "Header.msg" if package == "std_msgs"
                                                                  else "Pose.msg"))][:1]


def gazebo_msgs_path() -> str | None:
    """The folder to put on ``PYTHONPATH`` so that ``import gazebo_msgs`` finds worldgen's generated types (made
    on first use), or None when a real gazebo_msgs is importable. InputError naming the package to install when
    genpy or the standard message definitions are missing."""
    if system_has_gazebo_msgs():
        return None
    folder = cache_root() / f"gazebo_msgs-{_digest()}"
    if (folder / "gazebo_msgs" / "srv" / "__init__.py").is_file():
        return str(folder)
    _generate(folder)
    return str(folder)


def _generate(folder: Path) -> None:
    import_rospy()   # puts the system's ROS Python (genpy's folder) on sys.path when this is a venv
    try:
        import genpy.generate_initpy
        from genpy.generator import MsgGenerator, SrvGenerator
    except ImportError:
        raise InputError("genpy (ROS 1's message generator) is not installed, so gazebo_msgs cannot be made",
                         hint="apt install python3-genpy (ros-noetic-genpy with ROS's own packages)") from None
    search = {"gazebo_msgs": []}
    for package in DEPENDENCIES:
        dirs = _definition_dirs(package)
        if not dirs:
            raise InputError(f"the {package} message definitions (.msg files) are not installed",
                             hint=f"apt install ros-{package.replace('_', '-')}-dev (ros-noetic-{package.replace('_', '-')} "
                                  "with ROS's own packages)")
        search[package] = dirs
    folder.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=".gazebo_msgs-", dir=folder.parent))
    try:
        source = work / "definitions"
        (source / "msg").mkdir(parents=True)
        (source / "srv").mkdir()
        for name, text in MESSAGES.items():
            (source / "msg" / f"{name}.msg").write_text(text, encoding="utf-8")
        for name, text in SERVICES.items():
            (source / "srv" / f"{name}.srv").write_text(text, encoding="utf-8")
        search["gazebo_msgs"] = [str(source / "msg")]
        out = work / "python" / "gazebo_msgs"
        messages = sorted(str(p) for p in (source / "msg").glob("*.msg"))
        services = sorted(str(p) for p in (source / "srv").glob("*.srv"))
        quiet = _Quiet()
        with quiet:
            failed = MsgGenerator().generate_messages("gazebo_msgs", messages, str(out / "msg"), search) or \
                SrvGenerator().generate_messages("gazebo_msgs", services, str(out / "srv"), search)
        if failed:
            raise InputError(f"genpy could not generate gazebo_msgs: {quiet.text.strip()[-300:]}",
                             hint="please report this to the worldgen developers")
        for sub in ("msg", "srv"):
            genpy.generate_initpy.write_modules(str(out / sub))
        (out / "__init__.py").write_text("", encoding="utf-8")
        try:
            os.rename(work / "python", folder)
        except OSError:
            if not (folder / "gazebo_msgs" / "srv" / "__init__.py").is_file():   # not another process's, finished
                raise
    finally:
        shutil.rmtree(work, ignore_errors=True)


class _Quiet:
    """genpy prints each file it writes: kept from stdout (the report goes there), held for an error message."""

    def __enter__(self):
        import io

        self._old, self._buffer = sys.stdout, io.StringIO()
        sys.stdout = self._buffer
        return self

    def __exit__(self, *exc):
        sys.stdout = self._old
        self.text = self._buffer.getvalue()
