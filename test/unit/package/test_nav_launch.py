"""The SLAM and Navigation chapters' files: turtlebot3_slam.launch, turtlebot3_navigation.launch
(their parameters per model, ROBOTIS' values, the refusal, RViz only with a display), their RViz
configs, and the navigation extra's pins and patches (tools/nav_extra/). No ROS master; the
extra itself need not be installed (roslaunch --dump-params and --nodes do not start nodes)."""
import os
import re
import shutil
import subprocess

import pytest
import yaml
import unit_paths

ROOT = unit_paths.ROOT
NEEDS_ROSLAUNCH = pytest.mark.skipif(shutil.which("roslaunch") is None,
                                     reason="needs a ROS shell")


def roslaunch(option, launch_file, *args, env=None):
    done = subprocess.run(["roslaunch", option, "tutorial_turtlebot", launch_file] + list(args),
                          capture_output=True, text=True, timeout=60, env=env)
    return done.returncode, done.stdout, done.stderr


def params(launch_file, *args):
    status, out, err = roslaunch("--dump-params", launch_file, *args)
    assert status == 0, err
    return yaml.safe_load(out)


def config(name):
    with open(os.path.join(ROOT, "config", name)) as f:
        return yaml.safe_load(f)


@NEEDS_ROSLAUNCH
def test_slam_loads_robotis_gmapping_values():
    dumped = params("turtlebot3_slam.launch")
    node = "/turtlebot3_slam_gmapping/"
    for key, value in config("slam/gmapping.yaml").items():
        assert dumped[node + key] == value, key
    assert dumped[node + "maxUrange"] == 3.0 and dumped[node + "particles"] == 100
    assert (dumped[node + "base_frame"], dumped[node + "odom_frame"],
            dumped[node + "map_frame"]) == ("base_footprint", "odom", "map")


@NEEDS_ROSLAUNCH
def test_slam_refuses_other_methods_in_one_line():
    status, out, err = roslaunch("--nodes", "turtlebot3_slam.launch", "slam_methods:=karto")
    assert status != 0
    assert ("turtlebot3_slam.launch: slam_methods:=karto is not offered here; only gmapping is"
            in err.splitlines())


@NEEDS_ROSLAUNCH
@pytest.mark.parametrize("launch_file", ["turtlebot3_slam.launch",
                                         "turtlebot3_navigation.launch"])
def test_rviz_only_where_there_is_a_display(launch_file):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    assert "/rviz" not in roslaunch("--nodes", launch_file, env=env)[1].split()
    env["DISPLAY"] = ":99"
    assert "/rviz" in roslaunch("--nodes", launch_file, env=env)[1].split()
    assert "/rviz" not in roslaunch("--nodes", launch_file, "rviz:=false", env=env)[1].split()


@NEEDS_ROSLAUNCH
def test_slam_starts_no_second_robot_state_publisher():
    nodes = roslaunch("--nodes", "turtlebot3_slam.launch", "sim:=true", "rviz:=false")[1].split()
    assert nodes.count("/robot_state_publisher") == 1 and "/gazebo" in nodes
    assert "/robot_state_publisher" not in roslaunch("--nodes", "turtlebot3_slam.launch")[1]


@NEEDS_ROSLAUNCH
@pytest.mark.parametrize("model, footprint_x, max_vel_x, max_vel_theta, sim_time", [
    ("burger", -0.105, 0.22, 2.75, 1.5),
    ("waffle", -0.205, 0.26, 1.82, 2.0),
    ("waffle_pi", -0.205, 0.26, 1.82, 2.0),
])
def test_navigation_per_model(model, footprint_x, max_vel_x, max_vel_theta, sim_time):
    """ROBOTIS' costmap_common_params_<model> and dwa_local_planner_params_<model> values."""
    dumped = params("turtlebot3_navigation.launch", "model:=" + model)
    for costmap in ("global_costmap", "local_costmap"):
        footprint = dumped["/move_base/%s/footprint" % costmap]
        assert footprint[0][0] == footprint_x
        assert dumped["/move_base/%s/inflation_radius" % costmap] == 1.0
        assert dumped["/move_base/%s/scan/sensor_frame" % costmap] == "base_scan"
    assert dumped["/move_base/global_costmap/global_frame"] == "map"
    assert dumped["/move_base/local_costmap/global_frame"] == "odom"
    assert dumped["/move_base/local_costmap/rolling_window"] is True
    assert dumped["/move_base/DWAPlannerROS/max_vel_x"] == max_vel_x
    assert dumped["/move_base/DWAPlannerROS/max_vel_theta"] == max_vel_theta
    assert dumped["/move_base/DWAPlannerROS/sim_time"] == sim_time
    assert dumped["/move_base/DWAPlannerROS/xy_goal_tolerance"] == 0.05
    assert dumped["/move_base/base_local_planner"] == "dwa_local_planner/DWAPlannerROS"
    for key, value in config("navigation/amcl.yaml").items():
        assert dumped["/amcl/" + key] == value, key


@NEEDS_ROSLAUNCH
def test_navigation_args():
    dumped = params("turtlebot3_navigation.launch", "move_forward_only:=true",
                    "initial_pose_x:=-2.0", "scan_topic:=scan2")
    assert dumped["/move_base/DWAPlannerROS/min_vel_x"] == 0.0
    assert dumped["/amcl/initial_pose_x"] == -2.0
    assert dumped["/move_base/local_costmap/scan/topic"] == "scan2"
    assert dumped["/amcl/laser_max_range"] == 3.5     # ROBOTIS' amcl.launch


def rviz(name):
    with open(os.path.join(ROOT, "rviz", name)) as f:
        return yaml.safe_load(f)


def test_rviz_configs_show_the_map():
    for name in ("turtlebot3_slam.rviz", "turtlebot3_navigation.rviz"):
        manager = rviz(name)["Visualization Manager"]
        assert manager["Global Options"]["Fixed Frame"] == "map"
        topics = {d.get("Topic") for d in manager["Displays"]}
        assert {"/map", "/scan"} <= topics
    manager = rviz("turtlebot3_navigation.rviz")["Visualization Manager"]
    topics = {d.get("Topic") for d in manager["Displays"]}
    assert {"/particlecloud", "/move_base/NavfnROS/plan", "/move_base/global_costmap/costmap",
            "/move_base/local_costmap/costmap", "/move_base/DWAPlannerROS/local_plan"} <= topics
    tools = {t["Class"]: t.get("Topic") for t in manager["Tools"]}
    assert tools["rviz/SetInitialPose"] == "/initialpose"
    assert tools["rviz/SetGoal"] == "/move_base_simple/goal"


def test_pins_and_patches():
    with open(os.path.join(ROOT, "tools", "nav_extra", "pins")) as f:
        pins = [line.split() for line in f if line.strip() and not line.startswith("#")]
    assert {p[0] for p in pins} == {"openslam_gmapping", "slam_gmapping", "navigation"}
    for folder, repository, commit, *_ in pins:
        assert repository.endswith("/" + folder) and re.fullmatch(r"[0-9a-f]{40}", commit)
    folder = os.path.join(ROOT, "tools", "nav_extra", "patches")
    patches = sorted(os.listdir(folder))
    assert len(patches) == 3
    for name in patches:
        assert name.split("-")[0] in {p[0] for p in pins}
        with open(os.path.join(folder, name)) as f:
            why, after = f.readline(), f.readline()
        assert not why.startswith(("---", "diff")) and why.strip().endswith(".")
        assert after.startswith("--- a/"), name


def test_install_extra_offers_nav():
    done = subprocess.run(["bash", os.path.join(ROOT, "tools", "install_extra.sh")],
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 2 and "ray|train|nav" in done.stderr
