"""The physics is pinned: a fixed command sequence driven through Simulation gives the same
trajectory, and the same sensor readings (laser, IMU, odometry, wheels), to the last bit.

The digest below was taken before the stepping loop was reworked for speed (the ROS plumbing
moved off the physics core): any change to the step, the solver settings, the contacts, the
drive's control ticks or the ray casting changes it. If a change to the physics is meant, take
the new digest from the failure message and say why in the commit.
"""
import hashlib
import struct
from dataclasses import astuple

from tutorial_turtlebot.sim.simulation import SimConfig, Simulation

# (linear m/s, angular rad/s) held for 1 s of sim time each (400 steps of 2.5 ms): forward,
# an arc, backing while turning, stopped (the brake), then the Burger's top speeds.
COMMANDS = [(0.2, 0.0), (0.1, 1.0), (-0.15, -0.5), (0.0, 0.0), (0.22, 2.84)]
STEPS_PER_COMMAND = 400
# every float of a reading, in order
READINGS = {
    "imu": lambda robot: [v for part in astuple(robot.imu()) for v in part],
    "odom": lambda robot: [v for part in astuple(robot.odom()) for v in part],
    "joint_states": lambda robot: [v for part in robot.joint_states() for v in part],
}
PINNED = "8da7cf2909c4ef705fa0864af30308000a5083c49ecc832057506f4ec82e957d"


def trajectory_digest(ray_threads=1):
    """sha256 over the Burger's world pose (7 float64) after every step and every reading
    that falls due (scan ranges as float32, IMU, odometry and wheels as float64), in
    turtlebot3_world from its default spawn; the rays cast on ``ray_threads`` threads."""
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_world"))
    sim.physics.ray_threads = ray_threads
    digest = hashlib.sha256()
    try:
        for step in range(len(COMMANDS) * STEPS_PER_COMMAND):
            if step % STEPS_PER_COMMAND == 0:
                sim.command(*COMMANDS[step // STEPS_PER_COMMAND])
            for robot, name in sim.step():
                if robot is None:
                    continue
                if name == "scan":
                    digest.update(robot.scan().tobytes())
                elif name in READINGS:
                    values = READINGS[name](robot)
                    digest.update(struct.pack("<%dd" % len(values), *values))
            position, orientation = sim.robot.ground_truth()
            digest.update(struct.pack("<7d", *position, *orientation))
        return digest.hexdigest(), sim.robot.ground_truth()
    finally:
        sim.close()


def test_the_same_commands_give_the_same_trajectory_to_the_last_bit():
    digest, (position, _) = trajectory_digest()
    assert digest == PINNED, (
        "the trajectory changed (the Burger ended at x %.9f y %.9f); new digest %s"
        % (position[0], position[1], digest))


def test_rays_cast_on_two_threads_give_the_same_readings_to_the_last_bit():
    """As fast as possible the node casts a scan's rays on two threads (FAST_RAY_THREADS)."""
    assert trajectory_digest(ray_threads=2)[0] == PINNED


def test_the_digest_sees_a_change_of_one_command():
    """The check can fail: one command changed by 1 mm/s gives another digest."""
    original = COMMANDS[2]
    COMMANDS[2] = (original[0] + 0.001, original[1])
    try:
        assert trajectory_digest()[0] != PINNED
    finally:
        COMMANDS[2] = original
