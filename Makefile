# tutorial_turtlebot: two commands for a fresh machine.
#   make demo   set up, then the TurtleBot3 sim in turtlebot3_world with keyboard teleop
#   make test   set up, then every test: unit (pytest, no master) and rostest (the real sim)
#   make bench  set up, then the benchmark table
# Each target does its own set-up first (tools/setup.sh, idempotent).
SHELL := /bin/bash
WS := $(CURDIR)/.catkin_ws
ROS_ENV := source $(WS)/devel/setup.bash
MODEL ?= $(or $(TURTLEBOT3_MODEL),burger)

.PHONY: setup demo test unit rostest bench clean

setup:
	@bash tools/setup.sh

demo: setup
	@$(ROS_ENV) && roslaunch tutorial_turtlebot sim_teleop.launch model:=$(MODEL)

test: setup
	@$(ROS_ENV) && bash tools/run_tests.sh

unit: setup
	@$(ROS_ENV) && bash tools/run_tests.sh unit

rostest: setup
	@$(ROS_ENV) && bash tools/run_tests.sh rostest

bench: setup
	@$(ROS_ENV) && python3 bench/run_bench.py

clean:
	rm -rf $(WS)
