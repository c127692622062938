"""An SDF robot drives (world/model_plugins.DiffDriveRunner): test/fixtures/sdf_robot's model,
shaped like a TurtleBot3 Burger, spawned into an empty world and commanded through its
libgazebo_ros_diff_drive plugin: 0.1 m/s for 2 s goes 0.2 m, 1 rad/s turns it 2 rad, its
odometry is its pose (world) or its wheels' (encoder); reset, delete and respawn; the plugin
read with the robot's reading, a missing wheel joint one warning. No ROS master.
Units: m, s, rad."""
import math
from pathlib import Path

import pytest

from tutorial_turtlebot.sim import kinematics
from tutorial_turtlebot.sim.files import xml_reader
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_diff_drive import ModelDiffDrive
from tutorial_turtlebot.sim.files.plugins.world_model_plugins import read_model_plugins
from tutorial_turtlebot.sim.world.model_plugins import DiffDriveRunner
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

import unit_paths

MODEL = (Path(unit_paths.ROOT) / "test" / "fixtures" / "sdf_robot" / "model.sdf").read_text()
START = ((1.0, -0.5, 0.0), kinematics.quat_from_yaw(0.3))


@pytest.fixture()
def world():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    control = WorldControl(sim)
    yield sim, control
    sim.close()


def spawn(sim, control, text=MODEL, name="sdfbot"):
    warnings = control.spawn(name, text, START)
    drives = sim.model_plugins.drives(sim.time_ns)
    return warnings, next(d for d in drives if d.model.name == name)


def run(sim, seconds):
    for _ in range(round(seconds / sim.config.time_step)):
        sim.step()


def yaw(pose):
    return kinematics.yaw_from_quat(pose[1])


def test_the_plugin_is_read_with_the_robots_reading(world):
    sim, control = world
    _, drive = spawn(sim, control)
    spec = drive.spec
    assert isinstance(spec, ModelDiffDrive) and spec.model == "sdfbot"
    assert (spec.wheel_separation, spec.wheel_radius) == (0.160, 0.033)
    assert (spec.left_joint, spec.right_joint) == ("wheel_left_joint", "wheel_right_joint")
    assert (spec.command_topic, spec.odometry_topic, spec.odometry_frame,
            spec.robot_base_frame) == ("cmd_vel", "odom", "odom", "base_footprint")
    assert (spec.update_rate, spec.wheel_acceleration, spec.wheel_torque) == (30.0, 1.0, 10.0)
    assert drive.schedule.rate_hz == 30.0 and drive.namespace == ""


def test_forward_0_1_m_s_for_2_s_goes_0_2_m(world):
    sim, control = world
    _, drive = spawn(sim, control)
    run(sim, 0.5)                                  # settled on its wheels and caster
    start = sim.models.get("sdfbot").pose()
    drive.command(0.1, 0.0)
    run(sim, 2.0)
    end = sim.models.get("sdfbot").pose()
    travelled = math.dist(start[0][:2], end[0][:2])
    assert travelled == pytest.approx(0.2, rel=0.1)
    heading = math.atan2(end[0][1] - start[0][1], end[0][0] - start[0][0])
    assert abs(heading - yaw(start)) < 0.1         # forward is along its x
    odom = drive.odometry()
    assert odom.linear[0] == pytest.approx(0.1, rel=0.1)


def test_it_turns_in_place_at_1_rad_s(world):
    sim, control = world
    _, drive = spawn(sim, control)
    run(sim, 0.5)
    start = sim.models.get("sdfbot").pose()
    drive.command(0.0, 1.0)
    turned = 0.0
    last = yaw(start)
    for _ in range(20):                            # 2 s, unwrapped every 0.1 s
        run(sim, 0.1)
        now = yaw(sim.models.get("sdfbot").pose())
        turned += math.remainder(now - last, math.tau)
        last = now
    end = sim.models.get("sdfbot").pose()
    assert turned == pytest.approx(2.0, rel=0.1)
    assert math.dist(start[0][:2], end[0][:2]) < 0.03
    assert drive.odometry().angular[2] == pytest.approx(1.0, rel=0.1)


def test_world_odometry_is_the_pose_and_the_command_is_held(world):
    sim, control = world
    _, drive = spawn(sim, control)
    drive.command(0.15, 0.5)
    run(sim, 1.5)
    odom = drive.odometry()
    position, orientation = sim.models.get("sdfbot").pose()
    assert odom.position == pytest.approx(position, abs=1e-9)
    assert odom.orientation == pytest.approx(orientation, abs=1e-9)
    assert odom.linear[0] == pytest.approx(0.15, rel=0.1)       # held over 45 ticks
    assert odom.angular[2] == pytest.approx(0.5, rel=0.15)


def test_encoder_odometry_follows_the_wheels_from_zero(world):
    sim, control = world
    text = MODEL.replace("<odometrySource>world</odometrySource>",
                         "<odometrySource>encoder</odometrySource>")
    _, drive = spawn(sim, control, text)
    run(sim, 0.5)
    assert drive.odometry().position == pytest.approx((0.0, 0.0, 0.0), abs=2e-3)
    start = sim.models.get("sdfbot").pose()
    drive.command(0.1, 0.0)
    run(sim, 2.0)
    end = sim.models.get("sdfbot").pose()
    odom = drive.odometry()
    assert math.hypot(*odom.position[:2]) == pytest.approx(
        math.dist(start[0][:2], end[0][:2]), rel=0.05)
    assert odom.linear[0] == pytest.approx(0.1, rel=0.1)


def test_reset_world_stops_it_at_its_spawn_pose(world):
    sim, control = world
    _, drive = spawn(sim, control)
    drive.command(0.2, 0.0)
    run(sim, 1.0)
    sim.reset_world()
    run(sim, 1.0)                                  # the command is gone with the reset
    position, _ = sim.models.get("sdfbot").pose()
    assert math.dist(position[:2], START[0][:2]) < 0.01
    assert drive.drive.stopped


def test_delete_and_respawn_bring_a_new_drive(world):
    sim, control = world
    _, first = spawn(sim, control)
    first.command(0.1, 0.0)
    run(sim, 0.2)
    control.delete("sdfbot")
    assert sim.model_plugins.drives(sim.time_ns) == []
    _, second = spawn(sim, control)
    assert second is not first and isinstance(second, DiffDriveRunner)
    run(sim, 0.5)
    start = sim.models.get("sdfbot").pose()
    run(sim, 1.0)                                  # a new drive: no command yet
    assert math.dist(start[0][:2], sim.models.get("sdfbot").pose()[0][:2]) < 0.005
    second.command(0.1, 0.0)
    run(sim, 1.0)
    assert math.dist(start[0][:2], sim.models.get("sdfbot").pose()[0][:2]) > 0.07


def test_a_wheel_joint_the_model_lacks_is_one_warning(world):
    sim, control = world
    text = MODEL.replace("<leftJoint>wheel_left_joint</leftJoint>",
                         "<leftJoint>left_wheel_hinge</leftJoint>")
    control.spawn("sdfbot", text, START)
    assert sim.model_plugins.drives(sim.time_ns) == []
    plugin = next(p for p in xml_reader.parse(text, "model.sdf").iter()
                  if p.tag == "plugin" and "diff_drive" in p.get("filename", ""))
    warnings = []
    assert read_model_plugins("model.sdf", warnings, [plugin], "sdfbot", [],
                              ["wheel_left_joint", "wheel_right_joint"]) == []
    assert len(warnings) == 1 and "'left_wheel_hinge' is not a joint of model 'sdfbot'" \
        in warnings[0]


def test_a_static_model_with_a_drive_stands_and_the_world_runs_on(world):
    sim, control = world
    text = MODEL.replace('<model name="sdfbot">', '<model name="sdfbot"><static>true</static>')
    _, drive = spawn(sim, control, text)
    drive.command(0.2, 0.0)
    run(sim, 0.5)                                  # its ticks find no wheel to drive
    assert drive.wheels() == []
    assert math.dist(sim.models.get("sdfbot").pose()[0][:2], START[0][:2]) < 1e-9
