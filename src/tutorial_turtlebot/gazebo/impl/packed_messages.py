"""Messages whose layout never changes, kept serialized: only the changing fields are rewritten.

Replaces: genpy's serialization of the whole message at every Publisher.publish.

A genpy message is built field by field and serialized into a fresh buffer at every publish
(rospy's ``Publisher.publish``). The sim's high-rate messages (clock, IMU, odometry, TF, joint
states, laser scans) keep their frames, names and covariances for life, so each is serialized
once, here, by genpy itself (its layout is genpy's by construction), and then only the header's
sequence number and stamp and the measured values are written into the kept bytes with
``struct.pack_into``. The bytes are what rospy would send: the 4-byte length, then the message.

Each packer's ``bytes()`` is a snapshot (a subscriber that cannot take it now keeps it);
``message()`` decodes it back into the genpy message (tests, debugging).
"""
import struct
from io import BytesIO

import numpy as np
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

_U32 = struct.Struct("<I")
_STAMP = struct.Struct("<II")
_D3 = struct.Struct("<3d")
_D4 = struct.Struct("<4d")
_D7 = struct.Struct("<7d")


def _serialized(msg) -> bytearray:
    """``msg`` as rospy sends it: 4-byte little-endian length, then genpy's serialization."""
    buffer = BytesIO()
    msg.serialize(buffer)
    body = buffer.getvalue()
    return bytearray(_U32.pack(len(body)) + body)


def _string_size(text: str) -> int:
    """Bytes a ROS string takes: its 4-byte length and its UTF-8."""
    return 4 + len(text.encode("utf-8"))


class Packed:
    """A kept serialization of one message (``self.buffer``), rewritten in place."""

    message_type = None
    has_header = True

    def __init__(self, msg):
        self.buffer = _serialized(msg)

    def set_header_seq(self, seq: int) -> None:
        """The header's seq: rospy's count of the publisher's messages (publish_packed)."""
        _U32.pack_into(self.buffer, 4, seq & 0xFFFFFFFF)

    def set_stamp(self, secs: int, nsecs: int) -> None:
        """The header's stamp (s, ns of sim time)."""
        _STAMP.pack_into(self.buffer, 8, secs, nsecs)

    def bytes(self) -> bytes:
        return bytes(self.buffer)

    def message(self):
        """The genpy message these bytes decode to."""
        return self.message_type().deserialize(bytes(self.buffer[4:]))


class PackedClock(Packed):
    """rosgraph_msgs/Clock: the stamp only (no header)."""

    message_type = Clock
    has_header = False

    def __init__(self):
        super().__init__(Clock())

    def write(self, secs: int, nsecs: int) -> None:
        _STAMP.pack_into(self.buffer, 4, secs, nsecs)


class PackedImu(Packed):
    """sensor_msgs/Imu in ``frame``, its three covariance diagonals set to ``variance``."""

    message_type = Imu

    def __init__(self, frame: str, variance: float):
        msg = Imu()
        msg.header.frame_id = frame
        for covariance in (msg.orientation_covariance, msg.angular_velocity_covariance,
                           msg.linear_acceleration_covariance):
            covariance[0] = covariance[4] = covariance[8] = variance
        super().__init__(msg)
        start = 16 + _string_size(frame)
        self._orientation = start                       # 4 doubles, then 9 of covariance
        self._angular_velocity = start + 8 * (4 + 9)    # 3 doubles, then 9
        self._linear_acceleration = self._angular_velocity + 8 * (3 + 9)

    def write(self, orientation, angular_velocity, linear_acceleration) -> None:
        """Quaternion (x, y, z, w), rad/s and m/s^2, all in the IMU's frame."""
        buffer = self.buffer
        _D4.pack_into(buffer, self._orientation, *orientation)
        _D3.pack_into(buffer, self._angular_velocity, *angular_velocity)
        _D3.pack_into(buffer, self._linear_acceleration, *linear_acceleration)


class PackedOdometry(Packed):
    """nav_msgs/Odometry from ``frame`` to ``child_frame`` with a fixed pose covariance
    diagonal (x, y, z, roll, pitch, yaw) and a zero twist covariance."""

    message_type = Odometry

    def __init__(self, frame: str, child_frame: str, pose_covariance_diagonal):
        msg = Odometry()
        msg.header.frame_id = frame
        msg.child_frame_id = child_frame
        for i, value in enumerate(pose_covariance_diagonal):
            msg.pose.covariance[i * 7] = value
        super().__init__(msg)
        self._pose = 16 + _string_size(frame) + _string_size(child_frame)  # 3 + 4 doubles
        self._twist = self._pose + 8 * (7 + 36)                            # 3 + 3 doubles

    def write(self, position, orientation, linear, angular) -> None:
        """Pose (m; x, y, z, w) in ``frame``, twist (m/s, rad/s) in ``child_frame``."""
        buffer = self.buffer
        _D7.pack_into(buffer, self._pose, *position, *orientation)
        _D3.pack_into(buffer, self._twist, *linear)
        _D3.pack_into(buffer, self._twist + 24, *angular)


class PackedTransform(Packed):
    """tf2_msgs/TFMessage holding one transform from ``frame`` to ``child_frame``, as
    tf2_ros.TransformBroadcaster.sendTransform sends it (the transform's header seq stays 0:
    a TFMessage has no header of its own for rospy to number)."""

    message_type = TFMessage
    has_header = False

    def __init__(self, frame: str, child_frame: str):
        transform = TransformStamped()
        transform.header.frame_id = frame
        transform.child_frame_id = child_frame
        msg = TFMessage(transforms=[transform])
        super().__init__(msg)
        self._transform = 8 + 12 + _string_size(frame) + _string_size(child_frame)

    def write(self, secs: int, nsecs: int, translation, rotation) -> None:
        """Stamp (s, ns), translation (m) and rotation (x, y, z, w) of ``child_frame`` in
        ``frame``."""
        buffer = self.buffer
        _STAMP.pack_into(buffer, 12, secs, nsecs)
        _D7.pack_into(buffer, self._transform, *translation, *rotation)


class PackedJointState(Packed):
    """sensor_msgs/JointState of fixed ``names``: positions and velocities, no effort."""

    message_type = JointState

    def __init__(self, frame: str, names):
        names = list(names)
        count = len(names)
        msg = JointState(name=names, position=[0.0] * count, velocity=[0.0] * count)
        msg.header.frame_id = frame
        super().__init__(msg)
        after_names = 16 + _string_size(frame) + 4 + sum(_string_size(n) for n in names)
        self._positions = after_names + 4
        self._velocities = self._positions + 8 * count + 4
        self._doubles = struct.Struct("<%dd" % count)

    def write(self, positions, velocities) -> None:
        """Joint angles (rad) and rates (rad/s), in ``names``' order."""
        self._doubles.pack_into(self.buffer, self._positions, *positions)
        self._doubles.pack_into(self.buffer, self._velocities, *velocities)


class PackedLaserScan(Packed):
    """sensor_msgs/LaserScan of a fixed sweep: ``template`` gives every field but the stamp
    and the ranges (``samples`` of them, float32)."""

    message_type = LaserScan

    def __init__(self, template: LaserScan):
        self.samples = len(template.intensities)
        template.ranges = [0.0] * self.samples
        super().__init__(template)
        self._ranges = 16 + _string_size(template.header.frame_id) + 7 * 4 + 4
        self._ranges_end = self._ranges + 4 * self.samples

    def write(self, ranges: np.ndarray) -> None:
        """``samples`` ranges (m), written as little-endian float32."""
        self.buffer[self._ranges:self._ranges_end] = np.asarray(ranges, dtype="<f4").tobytes()
