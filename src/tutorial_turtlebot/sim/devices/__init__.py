"""The robot's devices as Gazebo's plugins model them: the differential drive, wheel odometry, the
laser and the camera. No ROS; the engine measures, these turn measurements into readings."""
