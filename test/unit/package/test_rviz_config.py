"""The RViz configs in rviz/ and which one ``sim.launch rviz:=true`` opens for each model."""
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml
import unit_paths

ROOT = Path(unit_paths.ROOT)
CONFIGS = ("turtlebot3.rviz", "turtlebot3_no_camera.rviz")


def load(name):
    return yaml.safe_load((ROOT / "rviz" / name).read_text(encoding="utf-8"))


def displays(config):
    return {d["Name"]: d for d in config["Visualization Manager"]["Displays"]}


@pytest.mark.parametrize("name", CONFIGS)
def test_odometry_stays_readable(name):
    """No covariance (Gazebo's 1e12 on z, roll, pitch paints the whole view) and a short
    trail of small arrows."""
    odom = displays(load(name))["Odometry"]
    assert odom["Class"] == "rviz/Odometry" and odom["Topic"] == "/odom"
    assert odom["Covariance"]["Value"] is False
    assert 1 <= odom["Keep"] <= 10
    assert odom["Shape"]["Shaft Length"] <= 0.3


@pytest.mark.parametrize("name", CONFIGS)
def test_what_a_turtlebot3_user_expects(name):
    config = load(name)
    shown = displays(config)
    assert config["Visualization Manager"]["Global Options"]["Fixed Frame"] == "odom"
    for display, cls in (("RobotModel", "rviz/RobotModel"), ("TF", "rviz/TF"),
                         ("LaserScan", "rviz/LaserScan"), ("Odometry", "rviz/Odometry")):
        assert shown[display]["Class"] == cls and shown[display]["Enabled"] is True
    assert shown["LaserScan"]["Topic"] == "/scan"
    assert shown["RobotModel"]["Robot Description"] == "robot_description"


def test_configs_differ_only_by_the_camera_panel():
    with_camera, without = load("turtlebot3.rviz"), load("turtlebot3_no_camera.rviz")
    camera = displays(with_camera).pop("Camera")
    assert camera["Class"] == "rviz/Image" and camera["Enabled"] is True
    assert camera["Image Topic"] == "/camera/rgb/image_raw"
    assert not any(d["Class"] in ("rviz/Image", "rviz/Camera")
                   for d in without["Visualization Manager"]["Displays"])
    with_camera["Visualization Manager"]["Displays"] = [
        d for d in with_camera["Visualization Manager"]["Displays"] if d["Name"] != "Camera"]
    with_camera["Window Geometry"].pop("Camera")
    assert with_camera == without


@pytest.mark.skipif(shutil.which("roslaunch") is None, reason="needs a ROS shell")
@pytest.mark.parametrize("args, config", [
    (["model:=burger"], "turtlebot3_no_camera.rviz"),
    (["model:=burger", "camera:=true"], "turtlebot3.rviz"),  # the AutoRace burger, 320x240
    (["model:=waffle"], "turtlebot3_no_camera.rviz"),  # 1920x1080: see sim.launch
    (["model:=waffle", "rviz_camera:=true"], "turtlebot3.rviz"),
    (["model:=waffle_pi"], "turtlebot3.rviz"),
    (["model:=waffle_pi", "camera:=false"], "turtlebot3_no_camera.rviz"),
    (["model:=waffle_pi", "rviz_camera:=false"], "turtlebot3_no_camera.rviz"),
])
def test_sim_launch_picks_the_config(args, config):
    done = subprocess.run(["roslaunch", "--args", "rviz", "tutorial_turtlebot", "sim.launch",
                           "rviz:=true"] + args, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "/rviz/%s " % config in done.stdout + " "


@pytest.mark.skipif(shutil.which("roslaunch") is None, reason="needs a ROS shell")
def test_no_rviz_by_default():
    done = subprocess.run(["roslaunch", "--nodes", "tutorial_turtlebot", "sim.launch",
                           "model:=waffle_pi"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "/rviz" not in done.stdout.split()
