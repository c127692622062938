"""The drives besides the diff drive on SDF models (world/model_drives.DriveRunner running
world/robot_drives' classes on an engine/drive_body.DriveBody): test/fixtures/sdf_drives'
skid-steer robot, planar-move puck and tricycle spawned into an empty world and commanded as
cmd_vel commands them; a force-based move on the puck; a missing wheel joint one warning;
reset and delete. No ROS master. Units: m, s, rad."""
import math
from pathlib import Path

import pytest

from tutorial_turtlebot.sim import kinematics
from tutorial_turtlebot.sim.files import xml_reader
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_planar_move import PlanarMovePlugin
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_skid_steer_drive import SkidSteerPlugin
from tutorial_turtlebot.sim.files.plugins.world_model_plugins import read_model_plugins
from tutorial_turtlebot.sim.world.model_plugins import MODEL_PLUGINS, DriveRunner
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

import unit_paths

FIXTURES = Path(unit_paths.ROOT) / "test" / "fixtures" / "sdf_drives"
SKID = (FIXTURES / "skid_steer.sdf").read_text()
PUCK = (FIXTURES / "planar_move.sdf").read_text()
TRIKE = (FIXTURES / "tricycle.sdf").read_text()
START = ((1.0, -0.5, 0.0), (0.0, 0.0, 0.0, 1.0))


@pytest.fixture()
def world():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim, WorldControl(sim)
    sim.close()


def spawn(world, text, name):
    """The drive of the SDF model ``text`` spawned as ``name`` at START, settled 0.5 s."""
    sim, control = world
    assert control.spawn(name, text, START) == []
    drive = next(d for d in sim.model_plugins.drives(sim.time_ns) if d.model.name == name)
    run(sim, 0.5)
    return drive


def run(sim, seconds, drive=None):
    """Step ``seconds`` of sim time; how many odometry ticks ``drive`` had."""
    ticks = 0
    for _ in range(round(seconds / sim.config.time_step)):
        if (None, MODEL_PLUGINS) in sim.step() and drive in sim.model_plugins.due_now:
            ticks += drive.odometry_due
    return ticks


def pose(sim, name):
    """(x, y, yaw) of the model frame in the world."""
    (x, y, _), orientation = sim.models.get(name).pose()
    return x, y, kinematics.yaw_from_quat(orientation)


def test_the_skid_steer_is_read_from_the_sdf_with_its_joints(world):
    sim, _ = world
    drive = spawn(world, SKID, "skidbot")
    spec = drive.spec
    assert isinstance(drive, DriveRunner) and isinstance(spec, SkidSteerPlugin)
    assert spec.model == "skidbot" and spec.wheel_joints == (
        "left_front_joint", "right_front_joint", "left_rear_joint", "right_rear_joint")
    assert (spec.wheel_separation, spec.wheel_diameter, spec.torque) == (0.35, 0.1, 10.0)
    assert drive.schedule.rate_hz == 100.0 and drive.publishes_odometry
    assert len(drive.body().wheels) == 4


def test_a_skid_steer_model_drives_forward_turns_left_and_its_odometry_follows(world):
    """0.3 m/s for 1 s: about 0.3 m along x (within 20 %), straight; then 1 rad/s turns it
    left where it stands; its odometry is its pose all along; stopped, it stands still."""
    sim, _ = world
    drive = spawn(world, SKID, "skidbot")
    x0, y0, yaw0 = pose(sim, "skidbot")
    drive.command(0.3, 0.0)
    assert run(sim, 1.0, drive) == 100                  # odometry at its updateRate
    x, y, yaw = pose(sim, "skidbot")
    assert x - x0 == pytest.approx(0.3, rel=0.2)
    assert abs(y - y0) < 0.02 and abs(yaw - yaw0) < 0.03
    odom = drive.odometry()
    assert odom.position[:2] == pytest.approx((x, y), abs=1e-3)
    assert odom.linear[0] == pytest.approx(0.3, rel=0.2)
    drive.command(0.0, 1.0)
    run(sim, 2.0)
    x2, y2, yaw2 = pose(sim, "skidbot")
    assert math.remainder(yaw2 - yaw, math.tau) > 0.5     # left: counterclockwise
    assert math.hypot(x2 - x, y2 - y) < 0.1                # about where it stood
    odom = drive.odometry()
    assert odom.position[:2] == pytest.approx((x2, y2), abs=1e-3)
    assert kinematics.yaw_from_quat(odom.orientation) == pytest.approx(yaw2, abs=1e-3)
    assert odom.angular[2] > 0.3
    drive.command(0.0, 0.0)
    run(sim, 0.5)
    held = pose(sim, "skidbot")
    run(sim, 1.0)
    assert pose(sim, "skidbot") == pytest.approx(held, abs=1e-3)


def test_a_planar_move_model_moves_sideways_on_a_y_command(world):
    """linear.y 0.2 m/s for 1 s: 0.2 m to its left (+y), none forward; odometry at 20 Hz
    with the commanded twist."""
    sim, _ = world
    drive = spawn(world, PUCK, "puck")
    assert isinstance(drive.spec, PlanarMovePlugin) and drive.spec.model == "puck"
    x0, y0, yaw0 = pose(sim, "puck")
    drive.command(0.0, 0.0, 0.2)
    assert run(sim, 1.0, drive) == pytest.approx(20, abs=1)
    x, y, yaw = pose(sim, "puck")
    assert y - y0 == pytest.approx(0.2, rel=0.05)
    assert abs(x - x0) < 0.005 and abs(yaw - yaw0) < 0.005
    odom = drive.odometry()
    assert odom.linear[:2] == pytest.approx((0.0, 0.2), abs=0.01)
    assert odom.position[:2] == pytest.approx((x, y), abs=0.02)   # at its last 20 Hz tick


def test_a_force_based_move_model_is_pushed_to_the_commanded_velocity(world):
    """The puck with hector's force-based move: 0.3 m/s forward, 0.1 m/s left, 0.5 rad/s
    reached within 5 % after 1 s."""
    sim, _ = world
    text = PUCK.replace("libgazebo_ros_planar_move.so", "libgazebo_ros_force_based_move.so")
    drive = spawn(world, text, "puck")
    drive.command(0.3, 0.5, 0.1)
    run(sim, 1.0)
    (vx, vy, _), (_, _, wz) = sim.models.get("puck").twist()
    yaw = pose(sim, "puck")[2]
    forward = vx * math.cos(yaw) + vy * math.sin(yaw)
    left = vy * math.cos(yaw) - vx * math.sin(yaw)
    assert (forward, left, wz) == pytest.approx((0.3, 0.1, 0.5), rel=0.05)


def test_a_tricycle_model_drives_forward_and_steers(world):
    """linear.x 0.3 m/s at the front wheel: about 0.3 m in 1 s; angular.z 0.5 is its steering
    angle: the yaw rate 0.3 sin(0.5) / 0.4 (its wheelbase) within 15 %; its four joints'
    states as publishWheelJointState asks."""
    sim, _ = world
    drive = spawn(world, TRIKE, "trike")
    x0, y0, _ = pose(sim, "trike")
    drive.command(0.3, 0.0)
    run(sim, 1.0)
    x, y, _ = pose(sim, "trike")
    assert x - x0 == pytest.approx(0.3, rel=0.1) and abs(y - y0) < 0.01
    drive.command(0.3, 0.5)
    run(sim, 0.5)                                        # the steering turns
    yaw1 = pose(sim, "trike")[2]
    run(sim, 1.0)
    yaw2 = pose(sim, "trike")[2]
    assert yaw2 - yaw1 == pytest.approx(0.3 * math.sin(0.5) / 0.4, rel=0.15)
    names, positions, velocities = drive.joint_states()
    assert names == ("front_steering_joint", "front_wheel_joint", "left_wheel_joint",
                     "right_wheel_joint")
    assert positions[0] == pytest.approx(0.5, abs=0.01)
    assert velocities[1] == pytest.approx(0.3 / 0.05, rel=0.05)


def test_reset_world_stops_it_and_delete_takes_its_drive(world):
    sim, control = world
    drive = spawn(world, SKID, "skidbot")
    drive.command(0.3, 0.0)
    run(sim, 1.0)
    sim.reset_world()
    run(sim, 1.0)                                        # the command went with the reset
    x, y, _ = pose(sim, "skidbot")
    assert math.hypot(x - START[0][0], y - START[0][1]) < 0.01
    control.delete("skidbot")
    assert sim.model_plugins.drives(sim.time_ns) == []


def test_a_wheel_joint_the_model_lacks_is_one_warning_and_no_drive(world):
    sim, control = world
    text = SKID.replace("<leftRearJoint>left_rear_joint</leftRearJoint>",
                        "<leftRearJoint>rear_left_hinge</leftRearJoint>")
    control.spawn("skidbot", text, START)
    assert sim.model_plugins.drives(sim.time_ns) == []
    plugin = next(p for p in xml_reader.parse(text, "skid_steer.sdf").iter()
                  if p.tag == "plugin")
    warnings = []
    assert read_model_plugins("skid_steer.sdf", warnings, [plugin], "skidbot", [],
                              ["left_front_joint", "right_front_joint", "left_rear_joint",
                               "right_rear_joint"]) == []
    assert len(warnings) == 1
    assert "<leftRearJoint> 'rear_left_hinge' is not a joint of model 'skidbot'" in warnings[0]


def test_the_yaw_inertia_is_about_the_model_z_axis_whatever_the_principal_axes(world):
    """The base is built along its principal axes; the drive's yaw inertia is still the one
    about the model's z: an inertia of moments (0.01, 0.02, 0.03) turned 90 degrees about y
    puts its 0.01 about z."""
    turned = PUCK.replace(
        "<inertia><ixx>0.017</ixx><iyy>0.017</iyy><izz>0.03</izz></inertia>",
        "<pose>0 0 0 0 1.5707963267948966 0</pose>"
        "<inertia><ixx>0.01</ixx><iyy>0.02</iyy><izz>0.03</izz></inertia>")
    assert turned != PUCK
    drive = spawn(world, turned, "puck")
    mass, yaw_inertia = drive.body().mass_and_yaw_inertia()
    assert mass == pytest.approx(2.0)
    assert yaw_inertia == pytest.approx(0.01, abs=1e-6)
