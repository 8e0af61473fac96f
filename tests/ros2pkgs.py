"""ROS 2 packages for tests, written in the shapes turtlebot3_gazebo's own use (humble: gazebo_ros's
gzserver.launch.py and spawn_entity.py; jazzy: ros_gz_sim's gz_sim.launch.py and create), with worlds to match."""

from __future__ import annotations

import textwrap
from pathlib import Path

LICENCE_HEADER = "# A class package for the worldgen tests.\n"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return path


def room_sdf(size: float = 4.0, version: str = "1.6", centre=(0.0, 0.0), gz_sim: bool = False,
             extra: str = "") -> str:
    """A square room of four 0.5 m walls (centre-lines ``size`` apart) round ``centre``; with ``gz_sim`` the world
    is written as Gazebo Sim worlds are (system plugins, Fuel's Ground Plane and Sun, a gpu_lidar sensor)."""
    cx, cy = centre
    h = size / 2
    walls = [((cx, cy - h), size, 0.0), ((cx + h, cy), size, 1.5708), ((cx, cy + h), size, 0.0),
             ((cx - h, cy), size, 1.5708)]
    links = "".join(f"""
      <link name='wall_{i}'>
        <pose>{x} {y} 0.25 0 0 {yaw}</pose>
        <collision name='c'><geometry><box><size>{length} 0.15 0.5</size></box></geometry></collision>
        <visual name='v'><geometry><box><size>{length} 0.15 0.5</size></box></geometry></visual>
      </link>""" for i, ((x, y), length, yaw) in enumerate(walls))
    if gz_sim:
        head = """
    <plugin filename="gz-sim-physics-system" name="gz::sim::systems::Physics"/>
    <plugin filename="gz-sim-user-commands-system" name="gz::sim::systems::UserCommands"/>
    <plugin filename="gz-sim-scene-broadcaster-system" name="gz::sim::systems::SceneBroadcaster"/>
    <plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors">
      <render_engine>ogre2</render_engine>
    </plugin>
    <include>
      <uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane</uri>
    </include>
    <include>
      <uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri>
    </include>
    <model name='lidar_post'>
      <static>true</static>
      <pose>9 9 0 0 0 0</pose>
      <link name='link'>
        <sensor name='scan' type='gpu_lidar'>
          <topic>scan</topic>
          <lidar><scan><horizontal><samples>360</samples></horizontal></scan>
            <range><min>0.12</min><max>3.5</max></range></lidar>
        </sensor>
      </link>
    </model>"""
    else:
        head = """
    <model name='ground_plane'>
      <static>1</static>
      <link name='link'>
        <collision name='collision'><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        </collision>
      </link>
    </model>"""
    return f"""<?xml version='1.0'?>
<sdf version='{version}'>
  <world name='default'>{head}
    <model name='room'>
      <static>1</static>{links}
    </model>{extra}
  </world>
</sdf>
"""


def manifest(name: str, build_type: str, depends=("rclpy",), exec_depends=(), model_path: bool = False) -> str:
    deps = "".join(f"  <depend>{d}</depend>\n" for d in depends)
    execs = "".join(f"  <exec_depend>{d}</exec_depend>\n" for d in exec_depends)
    tool = "ament_cmake" if build_type == "ament_cmake" else "ament_python"
    return (f'<?xml version="1.0"?>\n<package format="3">\n  <name>{name}</name>\n  <version>0.1.0</version>\n'
            f"  <description>A class world for the TurtleBot3.</description>\n"
            f'  <maintainer email="ta@example.edu">Teaching Assistant</maintainer>\n  <license>MIT</license>\n'
            + (f"  <buildtool_depend>{tool}</buildtool_depend>\n" if tool == "ament_cmake" else "")
            + deps + execs + f"  <export>\n    <build_type>{build_type}</build_type>\n"
            + ('    <gazebo_ros gazebo_model_path="${prefix}/models"/>\n' if model_path else "")
            + "  </export>\n</package>\n")


def python_package(root: Path, name: str, launch: dict, worlds: dict, scripts=("drive",),
                   exec_depends=("gazebo_ros", "ros_gz_sim")) -> Path:
    """An ament_python package as ros2 pkg create makes it, installing launch/ and worlds/ through data_files."""
    pkg = root / name
    write(pkg / "package.xml", manifest(name, "ament_python", exec_depends=exec_depends))
    write(pkg / "resource" / name, "")
    write(pkg / name / "__init__.py", "")
    write(pkg / "setup.cfg", f"""
        [develop]
        script_dir=$base/lib/{name}
        [install]
        install_scripts=$base/lib/{name}
        """)
    console = ", ".join(f"'{s} = {name}.{s}:main'" for s in scripts)
    write(pkg / "setup.py", f"""
        import os
        from glob import glob

        from setuptools import find_packages, setup

        package_name = '{name}'

        setup(
            name=package_name,
            version='0.1.0',
            packages=find_packages(exclude=['test']),
            data_files=[
                ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
                ('share/' + package_name, ['package.xml']),
                (os.path.join('share', package_name, 'launch'), glob(os.path.join('launch', '*launch.[pxy][yma]*'))),
                (os.path.join('share', package_name, 'worlds'), glob('worlds/*')),
            ],
            install_requires=['setuptools'],
            zip_safe=True,
            entry_points={{'console_scripts': [{console}]}},
        )
        """)
    for file, text in launch.items():
        write(pkg / "launch" / file, text)
    for file, text in worlds.items():
        write(pkg / "worlds" / file, text)
    return pkg


def cmake_package(root: Path, name: str, launch: dict, worlds: dict, models: bool = False) -> Path:
    """An ament_cmake package installing launch/ and worlds/ (and models/, exported as Gazebo's model path) to
    share/NAME."""
    pkg = root / name
    write(pkg / "package.xml", manifest(name, "ament_cmake", exec_depends=("ros_gz_sim", "ros_gz_bridge",
                                                                          "ros_gz_image"), model_path=models))
    write(pkg / "CMakeLists.txt", f"""
        cmake_minimum_required(VERSION 3.8)
        project({name})

        find_package(ament_cmake REQUIRED)

        install(DIRECTORY launch worlds{" models" if models else ""}
          DESTINATION share/${{PROJECT_NAME}}/
        )

        ament_package()
        """)
    for file, text in launch.items():
        write(pkg / "launch" / file, text)
    for file, text in worlds.items():
        write(pkg / "worlds" / file, text)
    return pkg


# ----------------------------------------------------------------------------------------- launch files

def humble_launch(package: str, world: str = "room.world", x: str = "1.0", y: str = "0.5") -> str:
    """Gazebo Classic (Humble): the world passed to gazebo_ros's gzserver.launch.py, the robot spawned with
    spawn_entity.py at constant -x/-y."""
    return f"""
        import os

        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        from launch.actions import IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch_ros.actions import Node


        def generate_launch_description():
            gazebo_ros = get_package_share_directory('gazebo_ros')
            world = os.path.join(get_package_share_directory('{package}'), 'worlds', '{world}')
            model = os.environ.get('TURTLEBOT3_MODEL', 'burger')

            server = IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(gazebo_ros, 'launch', 'gzserver.launch.py')),
                launch_arguments={{'world': world}}.items(),
            )
            client = IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(gazebo_ros, 'launch', 'gzclient.launch.py')))
            spawner = Node(
                package='gazebo_ros',
                executable='spawn_entity.py',
                arguments=['-entity', model, '-topic', 'robot_description',
                           '-x', '{x}', '-y', '{y}', '-z', '0.01'],
                output='screen',
            )
            return LaunchDescription([server, client, spawner])
        """


def jazzy_world_launch(package: str, world: str = "room.sdf", x: str = "-1.0", y: str = "0.5") -> str:
    """Gazebo Sim (Jazzy), as turtlebot3_world.launch.py: the world in gz_sim.launch.py's gz_args, the robot
    spawned by this package's spawn_robot.launch.py with x_pose/y_pose passed down."""
    return f"""
        import os

        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        from launch.actions import AppendEnvironmentVariable, IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch.substitutions import LaunchConfiguration


        def generate_launch_description():
            here = os.path.join(get_package_share_directory('{package}'), 'launch')
            ros_gz_sim = get_package_share_directory('ros_gz_sim')

            x_pose = LaunchConfiguration('x_pose', default='{x}')
            y_pose = LaunchConfiguration('y_pose', default='{y}')
            world = os.path.join(get_package_share_directory('{package}'), 'worlds', '{world}')

            sim_server = IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(ros_gz_sim, 'launch', 'gz_sim.launch.py')),
                launch_arguments={{'gz_args': ['-r -s -v2 ', world], 'on_exit_shutdown': 'true'}}.items(),
            )
            sim_gui = IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(ros_gz_sim, 'launch', 'gz_sim.launch.py')),
                launch_arguments={{'gz_args': '-g -v2 '}}.items(),
            )
            robot = IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(here, 'spawn_robot.launch.py')),
                launch_arguments={{'x_pose': x_pose, 'y_pose': y_pose}}.items(),
            )
            resources = AppendEnvironmentVariable(
                'GZ_SIM_RESOURCE_PATH', os.path.join(get_package_share_directory('{package}'), 'models'))

            description = LaunchDescription()
            description.add_action(sim_server)
            description.add_action(sim_gui)
            description.add_action(robot)
            description.add_action(resources)
            return description
        """


def jazzy_spawn_launch() -> str:
    """The included spawn file: x_pose/y_pose declared with defaults, ros_gz_sim's create at them."""
    return """
        import os

        from launch import LaunchDescription
        from launch.actions import DeclareLaunchArgument
        from launch.substitutions import LaunchConfiguration
        from launch_ros.actions import Node


        def generate_launch_description():
            model = os.environ['TURTLEBOT3_MODEL']
            x_pose = LaunchConfiguration('x_pose', default='0.0')
            y_pose = LaunchConfiguration('y_pose', default='0.0')

            declare_x = DeclareLaunchArgument('x_pose', default_value='0.0', description='x of the spawn')
            declare_y = DeclareLaunchArgument('y_pose', default_value='0.0', description='y of the spawn')
            create = Node(
                package='ros_gz_sim',
                executable='create',
                arguments=['-name', model, '-topic', 'robot_description',
                           '-x', x_pose, '-y', y_pose, '-z', '0.01'],
                output='screen',
            )
            bridge = Node(package='ros_gz_bridge', executable='parameter_bridge',
                          arguments=['/scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan'])
            camera = Node(package='ros_gz_image', executable='image_bridge', arguments=['/camera/image_raw'])

            description = LaunchDescription()
            description.add_action(declare_x)
            description.add_action(declare_y)
            description.add_action(create)
            description.add_action(bridge)
            description.add_action(camera) if model != 'burger' else None
            return description
        """


def declared_pose_launch(package: str, world: str = "room.world") -> str:
    """The spawn pose from DeclareLaunchArgument defaults (x 0.8, y -0.6, yaw 1.57), the world a launch argument
    whose default is a PathJoinSubstitution of FindPackageShare."""
    return f"""
        from launch import LaunchDescription
        from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch.substitutions import EnvironmentVariable, LaunchConfiguration, PathJoinSubstitution
        from launch_ros.actions import Node
        from launch_ros.substitutions import FindPackageShare

        WORLD_FILE = '{world}'


        def generate_launch_description():
            world = LaunchConfiguration('world')
            return LaunchDescription([
                DeclareLaunchArgument('x', default_value='0.8'),
                DeclareLaunchArgument('y', default_value='-0.6'),
                DeclareLaunchArgument('yaw', default_value='1.57'),
                DeclareLaunchArgument(
                    'world', default_value=PathJoinSubstitution([FindPackageShare('{package}'), 'worlds', WORLD_FILE])),
                IncludeLaunchDescription(
                    PythonLaunchDescriptionSource(
                        PathJoinSubstitution([FindPackageShare('gazebo_ros'), 'launch', 'gzserver.launch.py'])),
                    launch_arguments={{'world': world}}.items()),
                Node(package='gazebo_ros', executable='spawn_entity.py', name='spawner',
                     arguments=['-entity', EnvironmentVariable('TURTLEBOT3_MODEL', default_value='waffle'),
                                '-topic', 'robot_description',
                                '-x', LaunchConfiguration('x'), '-y', LaunchConfiguration('y'),
                                '-Y', LaunchConfiguration('yaw')]),
            ])
        """


def looped_launch(package: str, world: str = "room.world") -> str:
    """Several robots spawned in a for loop, as multi_robot.launch.py does: the world is read, the poses are not."""
    return f"""
        import os

        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        from launch.actions import IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch_ros.actions import Node


        def generate_launch_description():
            poses = [[-1.0, -0.5], [1.0, 0.5]]
            world = os.path.join(get_package_share_directory('{package}'), 'worlds', '{world}')
            description = LaunchDescription()
            description.add_action(IncludeLaunchDescription(
                PythonLaunchDescriptionSource(
                    os.path.join(get_package_share_directory('gazebo_ros'), 'launch', 'gzserver.launch.py')),
                launch_arguments={{'world': world}}.items()))
            for count, (x, y) in enumerate(poses):
                description.add_action(Node(
                    package='gazebo_ros', executable='spawn_entity.py',
                    arguments=['-entity', f'tb3_{{count}}', '-x', str(x), '-y', str(y)]))
            return description
        """


def unfollowed_call_launch(package: str, world: str = "room.world") -> str:
    """The spawn pose from a function of another module, which is not followed."""
    return f"""
        import os

        from ament_index_python.packages import get_package_share_directory
        from launch import LaunchDescription
        from launch.actions import IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch_ros.actions import Node

        from {package}.poses import start_pose


        def generate_launch_description():
            world = os.path.join(get_package_share_directory('{package}'), 'worlds', '{world}')
            x, y = start_pose('{world}')
            return LaunchDescription([
                IncludeLaunchDescription(
                    PythonLaunchDescriptionSource(
                        os.path.join(get_package_share_directory('gazebo_ros'), 'launch', 'gzserver.launch.py')),
                    launch_arguments={{'world': world}}.items()),
                Node(package='gazebo_ros', executable='spawn_entity.py',
                     arguments=['-entity', 'burger', '-x', str(x), '-y', str(y)]),
            ])
        """
