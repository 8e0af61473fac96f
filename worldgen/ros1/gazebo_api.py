"""Gazebo's ROS 1 interface on the simulated world (what gazebo_ros_api_plugin offers), answered as Gazebo answers:

================================  ==============================  ==========================================
name                              type                            does
================================  ==============================  ==========================================
``/gazebo/model_states``          gazebo_msgs/ModelStates         every model's pose and twist (world frame)
``/gazebo/link_states``           gazebo_msgs/LinkStates          every robot link's pose and twist
``/gazebo/set_model_state`` (in)  gazebo_msgs/ModelState          as the service, without an answer
``get_model_state``               gazebo_msgs/GetModelState       a model's pose and twist (world or relative)
``set_model_state``               gazebo_msgs/SetModelState       teleports a robot or an object, with a twist
``spawn_sdf_model``               gazebo_msgs/SpawnModel          an SDF model (box, cylinder, sphere, mesh …)
``spawn_urdf_model``              gazebo_msgs/SpawnModel          a URDF robot with a diff drive (a TurtleBot3),
                                                                  with its topics in ``robot_namespace``
``delete_model``                  gazebo_msgs/DeleteModel         removes a model or a robot (not the graded one)
``get_world_properties``          gazebo_msgs/GetWorldProperties  simulated time and model names
``pause_physics``/``unpause_…``   std_srvs/Empty                  simulated time stops / goes on
``reset_world``/``reset_simulation``  std_srvs/Empty              robots to their spawn poses, world models to
                                                                  their first poses (time keeps running)
================================  ==============================  ==========================================

Service calls arrive on rospy's threads; what they change is done by the simulation loop between two physics
steps (:meth:`GazeboApi.drain`), and the caller waits for it, as Gazebo applies requests between world updates.
"""

from __future__ import annotations

import queue
import threading

import numpy as np

from ..core import poses
from ..sim.models import matrix_of, pose_of
from .pose_msgs import fill_pose, fill_twist, pose7
from .spawner import spawn_model

CALL_TIMEOUT = 10.0   # s of real time a service call waits for the loop


class GazeboApi:
    """The services and topics in the module docstring, for the :class:`~.node.Bridge` ``bridge``."""

    def __init__(self, rospy, bridge):
        from gazebo_msgs.msg import LinkStates, ModelState, ModelStates
        from gazebo_msgs.srv import (DeleteModel, DeleteModelResponse, GetModelState, GetModelStateResponse,
                                     GetWorldProperties, GetWorldPropertiesResponse, SetModelState,
                                     SetModelStateResponse, SpawnModel, SpawnModelResponse)
        from std_srvs.srv import Empty, EmptyResponse

        self.rospy, self.bridge = rospy, bridge
        self.calls: queue.Queue = queue.Queue()
        self.types = {"ModelStates": ModelStates, "LinkStates": LinkStates, "GetModelState": GetModelStateResponse,
                      "SetModelState": SetModelStateResponse, "SpawnModel": SpawnModelResponse,
                      "DeleteModel": DeleteModelResponse, "GetWorldProperties": GetWorldPropertiesResponse,
                      "Empty": EmptyResponse}
        self.model_states = rospy.Publisher("/gazebo/model_states", ModelStates, queue_size=1)
        self.link_states = rospy.Publisher("/gazebo/link_states", LinkStates, queue_size=1)
        self.set_sub = rospy.Subscriber("/gazebo/set_model_state", ModelState,
                                        lambda msg: self.call(self.set_model_state, msg, wait=False))
        service = rospy.Service
        self.services = [
            service("/gazebo/get_model_state", GetModelState, lambda req: self.call(self.get_model_state, req)),
            service("/gazebo/set_model_state", SetModelState,
                    lambda req: self.call(self.set_model_state, req.model_state)),
            service("/gazebo/spawn_sdf_model", SpawnModel, lambda req: self.call(self.spawn, req, "sdf")),
            service("/gazebo/spawn_urdf_model", SpawnModel, lambda req: self.call(self.spawn, req, "urdf")),
            service("/gazebo/delete_model", DeleteModel, lambda req: self.call(self.delete_model, req)),
            service("/gazebo/get_world_properties", GetWorldProperties,
                    lambda req: self.call(self.world_properties, req)),
            service("/gazebo/pause_physics", Empty, lambda req: self.call(self.pause, True)),
            service("/gazebo/unpause_physics", Empty, lambda req: self.call(self.pause, False)),
            service("/gazebo/reset_world", Empty, lambda req: self.call(self.reset)),
            service("/gazebo/reset_simulation", Empty, lambda req: self.call(self.reset)),
        ]

    # -- threads ---------------------------------------------------------------------------------------------

    def call(self, fn, *args, wait: bool = True):
        """Run ``fn(*args)`` on the simulation loop's thread and return what it returns (rospy's thread waits)."""
        done, box = threading.Event(), {}
        self.calls.put((fn, args, done, box))
        if not wait:
            return None
        if not done.wait(CALL_TIMEOUT):
            raise self.rospy.ServiceException("the simulator did not answer in time")
        if "error" in box:
            raise self.rospy.ServiceException(box["error"])
        return box["value"]

    def drain(self) -> None:
        """Carry out the calls waiting (the simulation loop's thread, between steps)."""
        while not self.calls.empty():
            fn, args, done, box = self.calls.get_nowait()
            try:
                box["value"] = fn(*args)
            except Exception as err:   # noqa: BLE001  (a bad request fails its call, never the simulator)
                box["error"] = f"{type(err).__name__}: {err}"
            done.set()

    # -- entities --------------------------------------------------------------------------------------------

    def _robot(self, name: str):
        return next((t for t in self.bridge.robots if t.robot.name == name), None)

    def names(self) -> list[str]:
        session = self.bridge.session
        return session.models.names() + [r.name for r in session.robots]

    def entity_pose(self, name: str):
        """World pose (x y z qx qy qz qw) and twist of a model, a robot or ``model::link``; None when unknown."""
        session = self.bridge.session
        model, _, link = name.partition("::")
        robot = self._robot(model)
        if robot is not None:
            r = robot.robot
            index = r.link_index.get(link, None) if link else -1
            if index is None:
                return None
            position, orientation = r.link_pose(index)
            linear, angular = r.link_velocity(index)
            return (*position, *orientation), (linear, angular)
        if session.models.get(model) is None or link:
            return None
        return session.models.pose(model), session.models.twist(model)

    # -- services --------------------------------------------------------------------------------------------

    def get_model_state(self, req):
        res = self.types["GetModelState"]()
        res.header.stamp = self.bridge.stamp()
        res.header.frame_id = req.relative_entity_name
        found = self.entity_pose(req.model_name)
        if found is None:
            res.success, res.status_message = False, f"GetModelState: model [{req.model_name}] does not exist"
            return res
        pose, (linear, angular) = found
        if req.relative_entity_name not in ("", "world", "map", "/map"):
            ref = self.entity_pose(req.relative_entity_name)
            if ref is None:
                res.success = False
                res.status_message = (f"GetModelState: reference relative_entity_name "
                                      f"[{req.relative_entity_name}] not found, did you forget to scope the body "
                                      "by model name?")
                return res
            ref_t = matrix_of(ref[0])
            pose = pose_of(poses.inverse(ref_t) @ matrix_of(pose))
            rot = ref_t[:3, :3].T
            linear = tuple(rot @ (np.asarray(linear) - np.asarray(ref[1][0])))
            angular = tuple(rot @ (np.asarray(angular) - np.asarray(ref[1][1])))
        fill_pose(res.pose, pose)
        fill_twist(res.twist, linear, angular)
        res.success, res.status_message = True, "GetModelState: got properties"
        return res

    def set_model_state(self, state):
        res = self.types["SetModelState"]()
        name, session = state.model_name, self.bridge.session
        robot = self._robot(name)
        if robot is None and session.models.get(name) is None:
            res.success, res.status_message = False, f"SetModelState: model [{name}] does not exist"
            return res
        target = matrix_of(pose7(state.pose))
        linear = (state.twist.linear.x, state.twist.linear.y, state.twist.linear.z)
        angular = (state.twist.angular.x, state.twist.angular.y, state.twist.angular.z)
        if state.reference_frame not in ("", "world", "map", "/map"):
            ref = self.entity_pose(state.reference_frame)
            if ref is None:
                res.success = False
                res.status_message = (f"Updating ModelState: reference frame [{state.reference_frame}] not found, "
                                      "did you forget to scope the link by model name?")
                return res
            ref_t = matrix_of(ref[0])
            target = ref_t @ target
            linear, angular = tuple(ref_t[:3, :3] @ linear), tuple(ref_t[:3, :3] @ angular)
        if robot is not None:
            r = robot.robot
            position, orientation = r.base_to_root(target[:3, 3].tolist(), list(poses.matrix_quat(target[:3, :3])))
            r.teleport(position, orientation, linear, angular, keep_command=True)
            robot.last_velocity = None
        else:
            session.models.set_pose(name, target, linear, angular)
        res.success, res.status_message = True, "SetModelState: set model state done"
        return res

    def spawn(self, req, kind: str):
        res = self.types["SpawnModel"]()
        res.success, res.status_message = spawn_model(self.bridge, req, kind)
        return res

    def delete_model(self, req):
        res = self.types["DeleteModel"]()
        session, name = self.bridge.session, req.model_name
        robot = self._robot(name)
        if robot is not None and robot is self.bridge.robots[0]:
            res.success = False
            res.status_message = f"DeleteModel: worldgen keeps [{name}], the robot under test, in the world"
        elif robot is not None:
            self.bridge.remove_robot(robot)
            res.success, res.status_message = True, "DeleteModel: successfully deleted model"
        elif session.models.get(name) is not None:
            session.models.delete(name)
            res.success, res.status_message = True, "DeleteModel: successfully deleted model"
        else:
            res.success, res.status_message = False, "DeleteModel: model does not exist"
        return res

    def world_properties(self, _req):
        res = self.types["GetWorldProperties"]()
        res.sim_time, res.model_names, res.rendering_enabled = self.bridge.session.t, self.names(), False
        res.success, res.status_message = True, "GetWorldProperties: got properties"
        return res

    def pause(self, paused: bool):
        self.bridge.paused = paused
        return self.types["Empty"]()

    def reset(self):
        self.bridge.reset_world()
        return self.types["Empty"]()

    # -- topics ----------------------------------------------------------------------------------------------

    def states_heard(self) -> bool:
        return bool(self.model_states.get_num_connections() or self.link_states.get_num_connections())

    def publish_states(self) -> None:
        """``/gazebo/model_states`` and ``/gazebo/link_states``, when anyone listens."""
        if self.model_states.get_num_connections():
            msg = self.types["ModelStates"]()
            for name in self.names():
                pose, (linear, angular) = self.entity_pose(name)
                msg.name.append(name)
                msg.pose.append(self._pose_msg(pose))
                msg.twist.append(self._twist_msg(linear, angular))
            self.model_states.publish(msg)
        if self.link_states.get_num_connections():
            msg = self.types["LinkStates"]()
            for topics in self.bridge.robots:
                for link in sorted(topics.robot.link_index, key=topics.robot.link_index.get):
                    pose, (linear, angular) = self.entity_pose(f"{topics.robot.name}::{link}")
                    msg.name.append(f"{topics.robot.name}::{link}")
                    msg.pose.append(self._pose_msg(pose))
                    msg.twist.append(self._twist_msg(linear, angular))
            self.link_states.publish(msg)

    @staticmethod
    def _pose_msg(pose):
        from geometry_msgs.msg import Pose

        msg = Pose()
        fill_pose(msg, pose)
        return msg

    @staticmethod
    def _twist_msg(linear, angular):
        from geometry_msgs.msg import Twist

        msg = Twist()
        fill_twist(msg, linear, angular)
        return msg
