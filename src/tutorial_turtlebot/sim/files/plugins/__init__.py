"""Gazebo plugins and sensors as a model declares them, read into plain data."""
