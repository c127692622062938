"""Where the package's data folders are (package_data): found beside the code, without rospkg."""
import os

from tutorial_turtlebot import package_data
from unit_paths import ROOT


def test_data_folders_are_found_beside_the_code_without_a_package_path(monkeypatch):
    # rospkg would walk all of ROS_PACKAGE_PATH at each call (some 20 ms of the sim's start-up);
    # in the source tree and a devel space the folders are two levels above the module.
    monkeypatch.setenv("ROS_PACKAGE_PATH", "")
    package_data._installed_root.cache_clear()
    try:
        for name in ("urdf", "worlds", "models"):
            found = package_data.data_dir(name)
            assert os.path.isdir(found)
            assert os.path.samefile(found, os.path.join(ROOT, name))
    finally:
        package_data._installed_root.cache_clear()
