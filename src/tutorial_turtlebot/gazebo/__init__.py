"""The ``/gazebo`` node: the simulator (``..sim``) talking ROS where Gazebo's plugins and
gazebo_ros do: topics, services, the clock and the publishing machinery."""
