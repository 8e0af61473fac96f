"""Worlds for Gazebo Sim (Harmonic, ROS 2 Jazzy): the Gazebo Classic world of :mod:`worldgen.sdf.writer`, made
into one that ``gz sim`` runs.

The writer's world is taken as it is written and changed in three ways, nothing else (so every wall, obstacle,
marking and pose is the writer's, byte for byte in its numbers):

* SDF 1.8 (Harmonic reads 1.6 too, but 1.8 is what it writes; 1.9 on request);
* the world's system plugins first, as Gazebo Sim loads no system a world does not name: physics, user commands
  (spawning the robot), the scene broadcaster (the GUI's view), sensors with the ``ogre2`` render engine (the
  TurtleBot3's ``gpu_lidar`` is rendered) and the IMU — the ``gz-sim-*-system`` libraries and
  ``gz::sim::systems::*`` classes of Harmonic, the set turtlebot3_gazebo's jazzy worlds load;
* each stock material script (``Gazebo/Grey`` …, which Gazebo Sim's renderer does not read) written as its colour
  (:data:`worldgen.core.materials.STOCK_COLORS`) in ``<ambient>``/``<diffuse>``, as the writer writes a colour;
  any other script is kept as written.

The ground plane and the sun stay inline, as the writer has them: no ``<include>`` of a Fuel model, so the world
loads offline. pybullet (``worldgen validate``) ignores the plugins and reads the colours as before.
"""

from __future__ import annotations

from lxml import etree

from ..core.materials import script_color
from ..core.numbers import format_numbers

GZ_SDF_VERSIONS = ("1.8", "1.9")
DEFAULT_GZ_SDF_VERSION = "1.8"

# (library, class, child elements): the systems of a Harmonic world, in the order they are written.
SYSTEMS = (
    ("gz-sim-physics-system", "gz::sim::systems::Physics", ()),
    ("gz-sim-user-commands-system", "gz::sim::systems::UserCommands", ()),
    ("gz-sim-scene-broadcaster-system", "gz::sim::systems::SceneBroadcaster", ()),
    ("gz-sim-sensors-system", "gz::sim::systems::Sensors", (("render_engine", "ogre2"),)),
    ("gz-sim-imu-system", "gz::sim::systems::Imu", ()),
)


def gzsim_world(classic_world: str, sdf_version: str = DEFAULT_GZ_SDF_VERSION) -> str:
    """The Gazebo Sim world for the text of a world :func:`worldgen.sdf.writer.world_sdf` wrote (see the module
    docstring). Raises ValueError for an SDF version Gazebo Sim's worlds are not written in, or a text that is
    not a writer's world."""
    if sdf_version not in GZ_SDF_VERSIONS:
        raise ValueError(f"SDF version {sdf_version!r} is not one of {', '.join(GZ_SDF_VERSIONS)}")
    root = etree.fromstring(classic_world.encode("utf-8"), etree.XMLParser(remove_blank_text=True))
    world = root.find("world")
    if root.tag != "sdf" or world is None:
        raise ValueError("not a world written by worldgen.sdf.writer: no <sdf><world>")
    root.set("version", sdf_version)
    for index, (library, name, children) in enumerate(SYSTEMS):
        plugin = etree.Element("plugin", filename=library, name=name)
        for tag, text in children:
            etree.SubElement(plugin, tag).text = text
        world.insert(index, plugin)
    for material in world.iter("material"):
        _script_as_colour(material)
    head = classic_world[:classic_world.index("<sdf")]   # the writer's XML declaration, kept as it is
    return head + etree.tostring(root, pretty_print=True, encoding="unicode")


def _script_as_colour(material) -> None:
    """A ``<material>`` naming a stock script gets that script's colour instead (ambient and diffuse)."""
    script = material.find("script")
    if script is None:
        return
    colour = script_color(script.findtext("name"))
    if colour is None:
        return
    at = list(material).index(script)
    material.remove(script)
    for offset, tag in enumerate(("ambient", "diffuse")):
        element = etree.Element(tag)
        element.text = format_numbers(colour, 6, point=False)
        material.insert(at + offset, element)

