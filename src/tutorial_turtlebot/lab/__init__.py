"""The lab's own nodes (move_turtlebot, laser_data, teleop_key, stop_at_obstacle, wander) and
their ROS-free logic (scan reading, obstacle and wander logic, keys to twists)."""
