"""sim.launch's enable_ros_network, as gazebo_ros' empty_world.launch passes it: the node's
~enable_ros_network, true unless set (roslaunch --dump-params, no master)."""
from test_launch_and_node_args import dump_params


def test_sim_launch_passes_enable_ros_network_to_the_node():
    assert dump_params("sim.launch")["/gazebo/enable_ros_network"] is True
    off = dump_params("sim.launch", "enable_ros_network:=false")
    assert off["/gazebo/enable_ros_network"] is False
