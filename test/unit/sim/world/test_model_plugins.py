"""Model plugins running in the simulation (world/model_plugins): the fixture world of
test/fixtures/model_plugins stepped without a robot, a p3d's pose against its link's, a joint
state publisher against get_joint_properties, hector's GPS on the ellipsoid and its IMU at
rest; spawned and deleted models' plugins, a robot's, and a reset. No ROS master.
Units: m, s, rad, deg."""
from pathlib import Path

import pytest

from tutorial_turtlebot.sim.files.plugins.gazebo_ros_p3d import P3dPlugin
from tutorial_turtlebot.sim.files.plugins.hector_gazebo_ros_gps import HectorGpsPlugin
from tutorial_turtlebot.sim.world import reference_frames as rf
from tutorial_turtlebot.sim.world.model_plugins import MODEL_PLUGINS, fix_of
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

import unit_paths

FIXTURES = Path(unit_paths.ROOT) / "test" / "fixtures" / "model_plugins"
CRATE = '''<sdf version="1.6"><model name="x"><link name="l"><inertial><mass>1</mass>
<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial><collision
name="c"><geometry><box><size>.2 .2 .2</size></box></geometry></collision></link>
<plugin name="truth" filename="libgazebo_ros_p3d.so"><bodyName>l</bodyName>
<topicName>crate_odom</topicName><updateRate>20</updateRate></plugin></model></sdf>'''


@pytest.fixture(scope="module")
def sim():
    simulation = Simulation(SimConfig(world=str(FIXTURES / "model_plugins.world"),
                                      spawn_robot=False))
    yield simulation
    simulation.close()


def plugin(sim, kind, model="pendulum"):
    return next(p for p in sim.model_plugins.plugins
                if p.kind == kind and (kind.startswith("hector") or p.model.name == model))


def run(sim, seconds):
    """Step ``seconds`` of sim time; how many times each plugin was due."""
    counts = {}
    for _ in range(round(seconds / sim.config.time_step)):
        if (None, MODEL_PLUGINS) in sim.step():
            for p in sim.model_plugins.due_now:
                counts[p.name] = counts.get(p.name, 0) + 1
    return counts


def test_each_plugin_runs_at_its_rate(sim):
    run(sim, 0.01)                               # each is due at its first step
    counts = run(sim, 0.2)
    steps = round(0.2 / sim.config.time_step)
    assert counts == {"pendulum::bob_p3d": 10, "pendulum::hinge_states": 10, "box::imu": 10,
                      "box::box_p3d": steps, "box::gps": 2}
    assert [p.namespace for p in sim.model_plugins.plugins] == ["", "pendulum", "box", "", "box"]


def test_p3d_is_the_links_pose_and_twist_in_the_world(sim):
    run(sim, 0.3)                                 # the pendulum swings
    odom = plugin(sim, "p3d").odometry()
    [(_, (position, orientation), (linear, angular))] = [
        s for s in sim.models.get("pendulum").link_states() if s[0] == "pendulum::bob"]
    assert odom.position == pytest.approx(position, abs=1e-9)
    assert odom.orientation == pytest.approx(orientation, abs=1e-6)
    assert odom.linear == pytest.approx(linear) and odom.angular == pytest.approx(angular)
    assert abs(odom.angular[1]) > 0.1 and odom.variance == 0.0


def test_p3d_in_another_link_with_offsets(sim):
    runner = plugin(sim, "p3d")
    base = runner.spec
    try:
        runner.spec = P3dPlugin("p", "pendulum", "bob", "t", "bob", "bob", (1.0, 2.0, 3.0))
        odom = runner.odometry()      # the bob in its own frame: at the offset, unturned
        assert odom.position == pytest.approx((1.0, 2.0, 3.0), abs=1e-9)
        assert abs(odom.orientation[3]) == pytest.approx(1.0)
        assert odom.linear == pytest.approx((0, 0, 0), abs=1e-9)
    finally:
        runner.spec = base


def test_joint_states_are_what_get_joint_properties_says(sim):
    run(sim, 0.25)
    names, positions, velocities = plugin(sim, "joint_states").joint_states()
    props = WorldControl(sim).get_joint_properties("hinge")
    assert names == ("hinge",)
    assert positions == pytest.approx(props.position) and velocities == pytest.approx(props.rate)
    assert abs(velocities[0]) > 0.1


def test_the_imu_at_rest_reads_gravitys_reaction_up():
    sim = Simulation(SimConfig(world=str(FIXTURES / "model_plugins.world"), spawn_robot=False))
    try:
        run(sim, 1.0)                                  # the box has settled
        imu = plugin(sim, "hector_imu")
        imu.imu(sim.time_ns)
        run(sim, 0.02)
        reading = imu.imu(sim.time_ns)
        assert reading.linear_acceleration == pytest.approx((0.0, 0.0, 9.8), abs=0.01)
        assert reading.angular_velocity == pytest.approx((0, 0, 0), abs=1e-3)
        assert abs(reading.orientation[3]) == pytest.approx(1.0, abs=1e-4)
    finally:
        sim.close()


def test_the_gps_moves_1e5_degrees_of_latitude_for_111_m_north():
    spec = HectorGpsPlugin("g", "m", "l", "l")
    lat0, lon0, alt0 = fix_of(spec, (0.0, 0.0, 0.0))
    assert (lat0, lon0, alt0) == (49.9, 8.9, 0.0)
    lat, lon, alt = fix_of(spec, (1.11, 0.0, 2.0))          # x is north at heading 0
    assert lat - lat0 == pytest.approx(1e-5, rel=5e-3) and lon == lon0 and alt == 2.0
    lat, lon, _ = fix_of(spec, (0.0, 1.0, 0.0))             # y is west
    assert lat == lat0 and lon < lon0
    east = HectorGpsPlugin("g", "m", "l", "l", reference_heading=90.0)
    lat, _, _ = fix_of(east, (0.0, 1.11, 0.0))              # turned: y is north
    assert lat - lat0 == pytest.approx(1e-5, rel=5e-3)


def test_the_gps_fix_of_the_box(sim):
    gps = plugin(sim, "hector_gps")
    fix = gps.fix(sim.time_ns)
    (x, y, z), _ = sim.models.get("box").link_states()[0][1]
    assert (fix.latitude, fix.longitude, fix.altitude) == pytest.approx(
        fix_of(gps.spec, (x, y, z)))
    assert fix.latitude > 49.9 and fix.velocity == pytest.approx((0, 0, 0), abs=1e-3)


def test_a_spawned_models_plugins_run_until_it_is_deleted():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    control = WorldControl(sim)
    try:
        control.spawn("crate", CRATE, ((1.0, 2.0, 0.5), rf.IDENTITY[1]))
        assert run(sim, 0.5) == {"crate::truth": 10}
        odom = plugin(sim, "p3d", "crate").odometry()
        assert odom.position[:2] == pytest.approx((1.0, 2.0), abs=1e-3)
        control.delete("crate")
        assert run(sim, 0.2) == {} and sim.model_plugins.plugins == []
    finally:
        sim.close()


def test_a_robots_plugins_are_in_its_namespace_and_reset():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    control = WorldControl(sim)
    try:
        urdf = (FIXTURES / "p3d_robot.urdf").read_text()
        control.spawn("rover", urdf, ((0.5, 0.0, 0.0), rf.IDENTITY[1]), kind="urdf",
                      robot_namespace="tb_p3d")
        assert run(sim, 1.0) == {"rover::ground_truth": 30, "rover::wheel_states": 20}
        truth, wheels = sim.model_plugins.plugins
        assert truth.namespace == wheels.namespace == "/tb_p3d/"
        odom = truth.odometry()
        assert odom.position[0] == pytest.approx(0.5, abs=0.01)
        assert wheels.joint_states()[0] == ("left_joint", "right_joint")
        sim.reset_world()
        assert truth.schedule.next_ns == sim.time_ns
    finally:
        sim.close()
