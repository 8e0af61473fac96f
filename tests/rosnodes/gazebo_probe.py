#!/usr/bin/env python3
"""Test node that uses Gazebo's ROS interface the way students' nodes do, and prints one JSON line.

    gazebo_probe.py teleport MODEL X Y YAW   set_model_state, then the pose on /odom and /gazebo/model_states
    gazebo_probe.py spawn X Y SIZE           front beam; spawn_sdf_model a box at (X, Y); front beam; delete it; front
    gazebo_probe.py pause                    /clock across pause_physics and unpause_physics
    gazebo_probe.py missing                  get/set/delete of a model that does not exist: Gazebo's answers
    gazebo_probe.py robots NS1 NS2           each robot's front beam; drive NS1 only; both odometries; tf frames
    gazebo_probe.py robot URDF_FILE X Y NS   spawn_urdf_model a robot in NS facing us; our front beam; drive it
    gazebo_probe.py reset X Y YAW            teleport the robot, then reset_world: /odom before and after
"""

import json
import math
import sys
import time

import rospy
from gazebo_msgs.msg import ModelState, ModelStates
from gazebo_msgs.srv import DeleteModel, GetModelState, GetWorldProperties, SetModelState, SpawnModel
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def service(name, kind):
    rospy.wait_for_service(name, timeout=20)
    return rospy.ServiceProxy(name, kind)


def wait_for_time():
    deadline = time.time() + 20
    while rospy.Time.now().to_sec() == 0 and time.time() < deadline:
        time.sleep(0.01)


def sim_sleep(seconds):
    end = rospy.Time.now().to_sec() + seconds
    while rospy.Time.now().to_sec() < end and not rospy.is_shutdown():
        time.sleep(0.01)


def next_message(topic, kind, after=None):
    """The first message on ``topic`` stamped after simulated time ``after``."""
    after = rospy.Time.now().to_sec() if after is None else after
    while True:
        msg = rospy.wait_for_message(topic, kind, timeout=20)
        stamp = msg.header.stamp.to_sec() if hasattr(msg, "header") else rospy.Time.now().to_sec()
        if stamp > after:
            return msg


def front(ns=""):
    scan = next_message(f"{ns}/scan", LaserScan)
    return scan.ranges[0]


def teleport(model, x, y, yaw):
    state = ModelState()
    state.model_name = model
    state.pose.position.x, state.pose.position.y = x, y
    state.pose.orientation.z, state.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    answer = service("/gazebo/set_model_state", SetModelState)(state)
    after = rospy.Time.now().to_sec()
    odom = next_message("/odom", Odometry, after)
    states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=20)
    i = states.name.index(model)
    got = service("/gazebo/get_model_state", GetModelState)(model, "")
    return {"success": answer.success, "status": answer.status_message,
            "odom": [odom.pose.pose.position.x, odom.pose.pose.position.y, yaw_of(odom.pose.pose.orientation)],
            "model_states": [states.pose[i].position.x, states.pose[i].position.y, yaw_of(states.pose[i].orientation)],
            "get_model_state": [got.pose.position.x, got.pose.position.y, yaw_of(got.pose.orientation), got.success,
                                got.status_message],
            "names": list(states.name)}


BOX = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="box">
    <static>true</static>
    <link name="link">
      <collision name="collision"><geometry><box><size>{s} {s} 0.5</size></box></geometry></collision>
      <visual name="visual"><geometry><box><size>{s} {s} 0.5</size></box></geometry></visual>
    </link>
  </model>
</sdf>
"""


def spawn(x, y, size):
    before = front()
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = x, y, 0.25
    pose.orientation.w = 1.0
    spawned = service("/gazebo/spawn_sdf_model", SpawnModel)("box_1", BOX.format(s=size), "", pose, "world")
    again = service("/gazebo/spawn_sdf_model", SpawnModel)("box_1", BOX.format(s=size), "", pose, "world")
    with_box = front()
    names = service("/gazebo/get_world_properties", GetWorldProperties)().model_names
    deleted = service("/gazebo/delete_model", DeleteModel)("box_1")
    after = front()
    return {"before": before, "with_box": with_box, "after": after, "spawned": [spawned.success, spawned.status_message],
            "again": [again.success, again.status_message], "deleted": [deleted.success, deleted.status_message],
            "names": list(names)}


def pause():
    before = rospy.wait_for_message("/clock", Clock, timeout=20).clock.to_sec()
    service("/gazebo/pause_physics", Empty)()
    first = rospy.wait_for_message("/clock", Clock, timeout=20).clock.to_sec()
    time.sleep(1.0)
    later = rospy.wait_for_message("/clock", Clock, timeout=20).clock.to_sec()
    service("/gazebo/unpause_physics", Empty)()
    time.sleep(0.5)
    resumed = rospy.wait_for_message("/clock", Clock, timeout=20).clock.to_sec()
    return {"before": before, "paused_first": first, "paused_later": later, "resumed": resumed}


def missing():
    got = service("/gazebo/get_model_state", GetModelState)("no_such_model", "")
    state = ModelState()
    state.model_name = "no_such_model"
    state.pose.orientation.w = 1.0
    setting = service("/gazebo/set_model_state", SetModelState)(state)
    deleted = service("/gazebo/delete_model", DeleteModel)("no_such_model")
    return {"get": [got.success, got.status_message], "set": [setting.success, setting.status_message],
            "delete": [deleted.success, deleted.status_message]}


def robots(ns1, ns2):
    frames = set()
    rospy.Subscriber("/tf", TFMessage, lambda m: frames.update((t.header.frame_id, t.child_frame_id)
                                                              for t in m.transforms))
    fronts = {ns1: front(ns1), ns2: front(ns2)}
    start = {ns: next_message(f"{ns}/odom", Odometry).pose.pose.position for ns in (ns1, ns2)}
    cmd = rospy.Publisher(f"{ns1}/cmd_vel", Twist, queue_size=1)
    deadline = time.time() + 10
    while cmd.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.05)
    twist = Twist()
    twist.linear.x = 0.15
    cmd.publish(twist)
    sim_sleep(2.0)
    cmd.publish(Twist())
    sim_sleep(1.0)
    end = {ns: next_message(f"{ns}/odom", Odometry).pose.pose.position for ns in (ns1, ns2)}
    moved = {ns: math.hypot(end[ns].x - start[ns].x, end[ns].y - start[ns].y) for ns in (ns1, ns2)}
    odom_frames = {ns: [m.header.frame_id, m.child_frame_id] for ns, m in
                   ((ns, next_message(f"{ns}/odom", Odometry)) for ns in (ns1, ns2))}
    scan_frames = {ns: next_message(f"{ns}/scan", LaserScan).header.frame_id for ns in (ns1, ns2)}
    return {"fronts": fronts, "moved": moved, "tf": sorted(frames), "odom_frames": odom_frames,
            "scan_frames": scan_frames}


def spawn_robot(urdf_file, x, y, ns):
    """A second TurtleBot3 from spawn_urdf_model, facing the first: the first one's LiDAR sees it; its own
    topics are in ``ns`` and its cmd_vel drives it (away, here); then it is deleted."""
    before = front()
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = 1.0, 0.0   # yaw pi: facing the first robot
    with open(urdf_file) as f:
        urdf = f.read()
    answer = service("/gazebo/spawn_urdf_model", SpawnModel)("second_robot", urdf, ns, pose, "world")
    seen = front()
    start = next_message(f"{ns}/odom", Odometry).pose.pose.position
    cmd = rospy.Publisher(f"{ns}/cmd_vel", Twist, queue_size=1)
    deadline = time.time() + 10
    while cmd.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.05)
    twist = Twist()
    twist.linear.x = -0.1   # backing away from us
    cmd.publish(twist)
    went = rospy.Time.now().to_sec()
    sim_sleep(2.0)
    cmd.publish(Twist())
    drove = rospy.Time.now().to_sec() - went   # 2 s, or more when this process was kept waiting for a CPU
    sim_sleep(0.5)
    end = next_message(f"{ns}/odom", Odometry).pose.pose.position
    states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=20)
    deleted = service("/gazebo/delete_model", DeleteModel)("second_robot")
    return {"spawned": [answer.success, answer.status_message], "before": before, "seen": seen,
            "start": [start.x, start.y], "end": [end.x, end.y], "drove_s": drove, "names": list(states.name),
            "deleted": [deleted.success, deleted.status_message], "after": front()}


def reset(x, y, yaw):
    teleport("turtlebot3_burger", x, y, yaw)
    moved = next_message("/odom", Odometry).pose.pose.position
    service("/gazebo/reset_world", Empty)()
    back = next_message("/odom", Odometry)
    return {"moved": [moved.x, moved.y], "back": [back.pose.pose.position.x, back.pose.pose.position.y,
                                                  yaw_of(back.pose.pose.orientation)],
            "time_after": rospy.Time.now().to_sec()}


def main():
    rospy.init_node("gazebo_probe", anonymous=True)
    wait_for_time()
    command, args = sys.argv[1], sys.argv[2:]
    if command == "teleport":
        result = teleport(args[0], float(args[1]), float(args[2]), float(args[3]))
    elif command == "spawn":
        result = spawn(float(args[0]), float(args[1]), float(args[2]))
    elif command == "pause":
        result = pause()
    elif command == "missing":
        result = missing()
    elif command == "robot":
        result = spawn_robot(args[0], float(args[1]), float(args[2]), args[3])
    elif command == "reset":
        result = reset(float(args[0]), float(args[1]), float(args[2]))
    else:
        result = robots(args[0], args[1])
    print(json.dumps(result))


if __name__ == "__main__":
    main()
