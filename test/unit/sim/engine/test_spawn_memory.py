"""Spawn/delete returns its memory: boxes (SDF) and robots (URDF with plugins) spawned and
deleted again and again through WorldControl, with the real pybullet physics. No ROS master.

pybullet frees little of a body on removeBody (its collision shapes, and the renderer's copy of
its visuals, stay): without reuse of deleted bodies RSS grew about 2 KB per box cycle and 20 KB
per robot cycle without the EGL renderer, 16 and 70 KB with it."""
import os

from tutorial_turtlebot.package_data import data_dir
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import rss_kb

BOX_CYCLES, ROBOT_CYCLES = 500, 60
MAX_GROWTH_KB = 400      # per run of cycles, after a warm-up


def growth_kb(cycle, n: int) -> int:
    for i in range(10):      # warm-up: caches and pools of the first spawns
        cycle(i)
    start = rss_kb()
    for i in range(n):
        cycle(i)
    return rss_kb() - start


def test_box_and_robot_cycles_return_their_memory():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))   # EGL loads where it can
    try:
        wc = WorldControl(sim)
        with open(os.path.join(data_dir("models"), "goal_box", "model.sdf")) as f:
            box = f.read()
        with open(os.path.join(data_dir("urdf"), "turtlebot3_burger.urdf")) as f:
            urdf = f.read()

        def box_cycle(i):
            wc.spawn("box", box, ((1.0 + i % 3, 1.0, 0.2), (0.0, 0.0, 0.0, 1.0)))
            sim.step()
            wc.delete("box")

        def robot_cycle(i):
            wc.spawn("tb3_1", urdf, ((-1.0, i % 3, 0.0), (0.0, 0.0, 0.0, 1.0)), kind="urdf",
                     robot_namespace="tb3_1")
            sim.step()
            wc.delete("tb3_1")

        box_kb = growth_kb(box_cycle, BOX_CYCLES)
        robot_kb = growth_kb(robot_cycle, ROBOT_CYCLES)
        assert box_kb < MAX_GROWTH_KB, "%d box cycles grew RSS by %d KB" % (BOX_CYCLES, box_kb)
        assert robot_kb < MAX_GROWTH_KB, ("%d robot cycles grew RSS by %d KB"
                                          % (ROBOT_CYCLES, robot_kb))
        assert sim.models.names() == ["ground_plane"]
    finally:
        sim.close()
