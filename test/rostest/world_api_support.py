"""Helpers for the world API rostest nodes: service proxies by name, states from
/gazebo/model_states, the sim's real-time factor measured on /clock. Wall-time limits."""
import math
import time

import rospy
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import (DeleteModel, GetLinkState, GetModelProperties, GetModelState,
                             GetPhysicsProperties, GetWorldProperties, SetLinkState,
                             SetModelState, SetPhysicsProperties, SpawnModel)
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from sim_test_support import Recorder, wait_for

SERVICES = {"get_model_state": GetModelState, "set_model_state": SetModelState,
            "get_link_state": GetLinkState, "set_link_state": SetLinkState,
            "get_world_properties": GetWorldProperties,
            "get_model_properties": GetModelProperties, "spawn_sdf_model": SpawnModel,
            "spawn_urdf_model": SpawnModel, "delete_model": DeleteModel,
            "get_physics_properties": GetPhysicsProperties,
            "set_physics_properties": SetPhysicsProperties, "reset_world": Empty,
            "reset_simulation": Empty, "pause_physics": Empty, "unpause_physics": Empty}


class Gazebo:
    """Proxies of /gazebo's services (``gz.get_model_state(...)``) and a model_states recorder."""

    def __init__(self):
        for name, srv in SERVICES.items():
            rospy.wait_for_service("/gazebo/" + name, timeout=30.0)
            setattr(self, name, rospy.ServiceProxy("/gazebo/" + name, srv))
        self.states = Recorder("/gazebo/model_states", ModelStates)
        self.clock = Recorder("/clock", Clock)

    def latest_states(self, timeout=10.0):
        return self.states.latest(timeout)

    def names(self, timeout=10.0):
        msg = self.latest_states(timeout)
        return list(msg.name) if msg else None

    def wait_names(self, predicate, timeout=20.0):
        """Wait (wall s) until the latest model_states names satisfy ``predicate``."""
        return wait_for(lambda: self.names() is not None and predicate(self.names()), timeout)

    def position(self, name):
        resp = self.get_model_state(model_name=name)
        assert resp.success, resp.status_message
        p = resp.pose.position
        return p.x, p.y, p.z

    def factor(self, wall_seconds=3.0):
        """Sim seconds per wall second over ``wall_seconds`` of /clock."""
        start = self.clock.latest(10.0).clock.to_sec()
        t0 = time.monotonic()
        time.sleep(wall_seconds)
        end = self.clock.latest(10.0).clock.to_sec()
        return (end - start) / (time.monotonic() - t0)


def quat_yaw(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
