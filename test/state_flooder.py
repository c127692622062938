#!/usr/bin/env python3
"""A hostile client for the rostests and the bench: publishes /gazebo/set_model_state for one
model (a finite pose at rest) as fast as it can for a number of wall seconds, then prints how
many messages it sent and ends. Talks to the master of $ROS_MASTER_URI (this machine's).

    state_flooder.py MODEL SECONDS [X Y]
"""
import sys
import time

import rospy
from gazebo_msgs.msg import ModelState
from geometry_msgs.msg import Point, Pose, Quaternion


def main():
    model, seconds = sys.argv[1], float(sys.argv[2])
    x, y = (float(v) for v in sys.argv[3:5]) if len(sys.argv) >= 5 else (0.0, 0.0)
    rospy.init_node("state_flooder", anonymous=True, disable_signals=True)
    pub = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=1000)
    deadline = time.monotonic() + 5.0
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    msg = ModelState(model_name=model, reference_frame="world",
                     pose=Pose(position=Point(x, y, 0.0), orientation=Quaternion(0, 0, 0, 1)))
    end = time.monotonic() + seconds
    sent = 0
    while time.monotonic() < end:
        pub.publish(msg)
        sent += 1
    print(sent, flush=True)
    rospy.signal_shutdown("done")


if __name__ == "__main__":
    main()
