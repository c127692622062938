"""ROS names without ROS (ros_names), against rosgraph.names where both answer."""
import pytest
import rosgraph.names

from tutorial_turtlebot.ros_names import is_legal_name, is_legal_namespace

NAMES = ["", "scan", "/scan", "~cmd_vel", "/tb3_0/scan", "tb3_0/", "a//b", "1scan", "sc an",
         "scan-1", "/", "~", "café"]


@pytest.mark.parametrize("name", NAMES)
def test_names_as_rosgraph_has_them(name):
    expected = rosgraph.names.is_legal_name(name)
    if not name.isascii():     # rosgraph's \w takes any letter; ROS's docs allow ASCII only
        expected = False
    assert is_legal_name(name) == expected


@pytest.mark.parametrize("namespace, legal", [
    ("", True), ("/", True), ("tb3_0", True), ("/tb3_0/", True), ("/a/b", True),
    ("a//b", False), ("0tb3", False), ("tb3 0", False), ("~tb3", False), ("/tb3-0", False),
    (None, False)])
def test_namespaces(namespace, legal):
    assert is_legal_namespace(namespace) is legal
