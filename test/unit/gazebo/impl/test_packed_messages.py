"""Kept serializations send exactly the bytes rospy would send for the same message. No ROS
master: a rospy publisher's own implementation with a socket pair as its one subscriber."""
import math
import random
import socket
import struct
from io import BytesIO

import numpy as np
import pytest
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from rospy.msg import serialize_message
from sensor_msgs.msg import Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

from tutorial_turtlebot.gazebo.impl.nonblocking_publisher import Backlog, make_nonblocking
from tutorial_turtlebot.gazebo.impl.packed_messages import (PackedClock, PackedImu,
                                                            PackedJointState, PackedLaserScan,
                                                            PackedOdometry, PackedTransform)

SEQ = 4_000_000_123


def rospy_bytes(msg, seq=SEQ) -> bytes:
    """What rospy's publisher writes for ``msg`` as its ``seq``-th message."""
    buffer = BytesIO()
    serialize_message(buffer, seq, msg)
    return buffer.getvalue()


def numbers(count, rng):
    return tuple(rng.uniform(-1e3, 1e3) for _ in range(count))


@pytest.fixture
def rng():
    return random.Random(7)


def stamped(packed, secs, nsecs):
    packed.set_header_seq(SEQ)
    packed.set_stamp(secs, nsecs)
    return packed.bytes()


def test_clock(rng):
    packed = PackedClock()
    for secs, nsecs in ((0, 0), (12, 345_000_000), (2 ** 32 - 1, 999_999_999)):
        packed.write(secs, nsecs)
        assert packed.bytes() == rospy_bytes(Clock(clock=rospy.Time(secs, nsecs)))


@pytest.mark.parametrize("frame", ["imu_link", "tb3_0/imu_link", "bras_ü"])
def test_imu(rng, frame):
    packed = PackedImu(frame, 1e-4)
    for _ in range(3):
        q, w, a = numbers(4, rng), numbers(3, rng), numbers(3, rng)
        packed.write(q, w, a)
        msg = Imu()
        msg.header.frame_id = frame
        msg.header.stamp = rospy.Time(5, 6)
        msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = q
        v = msg.angular_velocity
        v.x, v.y, v.z = w
        v = msg.linear_acceleration
        v.x, v.y, v.z = a
        for covariance in (msg.orientation_covariance, msg.angular_velocity_covariance,
                           msg.linear_acceleration_covariance):
            covariance[0] = covariance[4] = covariance[8] = 1e-4
        assert stamped(packed, 5, 6) == rospy_bytes(msg)


def test_odometry(rng):
    diagonal = (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)
    packed = PackedOdometry("tb3_1/odom", "tb3_1/base_footprint", diagonal)
    position, orientation, linear, angular = (numbers(3, rng), numbers(4, rng),
                                              numbers(3, rng), numbers(3, rng))
    packed.write(position, orientation, linear, angular)
    msg = Odometry()
    msg.header.frame_id, msg.child_frame_id = "tb3_1/odom", "tb3_1/base_footprint"
    msg.header.stamp = rospy.Time(100, 2_500_000)
    for i, value in enumerate(diagonal):
        msg.pose.covariance[i * 7] = value
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    p.x, p.y, p.z = position
    q.x, q.y, q.z, q.w = orientation
    t = msg.twist.twist
    t.linear.x, t.linear.y, t.linear.z = linear
    t.angular.x, t.angular.y, t.angular.z = angular
    assert stamped(packed, 100, 2_500_000) == rospy_bytes(msg)


def test_transform_as_the_broadcaster_sends_it(rng):
    packed = PackedTransform("odom", "base_footprint")
    translation, rotation = numbers(3, rng), numbers(4, rng)
    packed.write(7, 8, translation, rotation)
    transform = TransformStamped()
    transform.header.frame_id, transform.child_frame_id = "odom", "base_footprint"
    transform.header.stamp = rospy.Time(7, 8)
    v, r = transform.transform.translation, transform.transform.rotation
    v.x, v.y, v.z = translation
    r.x, r.y, r.z, r.w = rotation
    assert packed.bytes() == rospy_bytes(TFMessage([transform]))


def test_joint_state(rng):
    names = ["wheel_left_joint", "wheel_right_joint"]
    packed = PackedJointState("", names)
    positions, velocities = numbers(2, rng), numbers(2, rng)
    packed.write(positions, velocities)
    msg = JointState(name=names, position=list(positions), velocity=list(velocities))
    msg.header.stamp = rospy.Time(3, 4)
    assert stamped(packed, 3, 4) == rospy_bytes(msg)


def test_laser_scan_ranges_as_float32_with_inf_and_nan():
    template = LaserScan(angle_min=0.0, angle_max=6.2657, angle_increment=0.0174533,
                         range_min=0.12, range_max=3.5, intensities=[0.0] * 360)
    template.header.frame_id = "base_scan"
    packed = PackedLaserScan(template)
    ranges = np.random.default_rng(1).uniform(0.12, 3.5, 360).astype(np.float32)
    ranges[[3, 50]] = np.inf
    ranges[7] = np.nan
    packed.write(ranges)
    msg = LaserScan(angle_min=0.0, angle_max=6.2657, angle_increment=0.0174533,
                    range_min=0.12, range_max=3.5, intensities=[0.0] * 360,
                    ranges=ranges.tolist())
    msg.header.frame_id = "base_scan"
    msg.header.stamp = rospy.Time(9, 10)
    assert stamped(packed, 9, 10) == rospy_bytes(msg)
    decoded = packed.message()
    assert math.isnan(decoded.ranges[7]) and decoded.ranges[3] == math.inf


def test_publish_packed_numbers_and_sends_as_rospy_does():
    """The publisher's own sequence counts packed messages; no subscriber: nothing is sent
    and nothing counted, as rospy's publish."""
    publisher = rospy.Publisher("/packed_test_imu", Imu, queue_size=1)
    make_nonblocking(publisher, Backlog())
    packed = PackedImu("imu_link", 0.0)
    assert publisher.publish_packed(packed) is False and publisher.impl.seq == 0

    class Transport:
        def __init__(self, sock):
            self.socket, self.done, self.endpoint_id = sock, False, "/listener"
            self.stat_bytes = self.stat_num_msg = 0
            self.cleanup_cb = None

        def close(self):
            self.done = True

        def fileno(self):
            return self.socket.fileno()

        def set_cleanup_callback(self, callback):
            self.cleanup_cb = callback

    writer, reader = socket.socketpair()
    try:
        publisher.impl.add_connection(Transport(writer))
        for k in (1, 2):
            packed.set_stamp(k, 0)
            assert publisher.publish_packed(packed) is True
        data = reader.recv(1 << 16)
        frames = []
        while data:
            (length,) = struct.unpack_from("<I", data)
            frames.append(data[:4 + length])
            data = data[4 + length:]
        expected = []
        for k in (1, 2):
            msg = Imu()
            msg.header.frame_id, msg.header.stamp = "imu_link", rospy.Time(k, 0)
            expected.append(rospy_bytes(msg, seq=k))
        assert frames == expected
        assert publisher.impl.seq == 2
    finally:
        writer.close()
        reader.close()
        publisher.unregister()
