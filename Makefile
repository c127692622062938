# tutorial_turtlebot: two commands for a fresh machine.
#   make demo   set up, then the TurtleBot3 sim in turtlebot3_world with keyboard teleop
#   make test   set up, then every test: unit (pytest, no master) and rostest (the real sim)
#   make bench  set up, then the benchmark table
#   make corpus set up, then public Gazebo worlds through the sim (not in make test)
#   make peer   set up, then gazebo_ros_pkgs' own tests against the sim (not in make test)
#   make slam / make nav   set up, then the e-Manual's SLAM / Navigation chapter on the sim
#   make unit / make rostest   the two halves of make test
#   make plan   what the set-up would install here (nothing is installed)
# Each target does its own set-up first (tools/setup.sh, idempotent); the test targets also
# make the Python 3.8 venv for the unit tests where a Python 3.8 exists (tools/setup.sh --test).
SHELL := /bin/bash
WS := $(CURDIR)/catkin_ws
ROS_ENV := source $(WS)/devel/setup.bash
MODEL ?= $(or $(TURTLEBOT3_MODEL),burger)

.PHONY: setup setup-test plan demo test unit rostest bench clean

setup:
	@bash tools/setup.sh

setup-test:
	@bash tools/setup.sh --test

plan:
	@/usr/bin/python3 tools/setup_plan.py

demo: setup
	@$(ROS_ENV) && roslaunch tutorial_turtlebot sim_teleop.launch model:=$(MODEL)

test: setup-test
	@$(ROS_ENV) && bash tools/run_tests.sh

unit: setup-test
	@$(ROS_ENV) && bash tools/run_tests.sh unit

rostest: setup
	@$(ROS_ENV) && bash tools/run_tests.sh rostest

bench: setup
	@$(ROS_ENV) && python3 bench/run_bench.py

# make corpus: not part of make test. Public Gazebo worlds through the real sim, one table
# (bench/corpus.py); the corpus lies outside the repository (tools/corpus/fetch_corpus.py
# makes it). CORPUS_ARGS="--only NAME,NAME" runs some of them.
.PHONY: corpus
corpus: setup
	@$(ROS_ENV) && python3 bench/corpus.py $(CORPUS_ARGS)

# make peer: not part of make test. gazebo_ros_pkgs' own tests, unmodified, the sim standing in
# for gzserver (tools/peer/run_peer.py; doc/peer.md); the peer's tree lies outside the
# repository in $PEER_SRC (tools/peer/fetch_peer.py makes it). PEER_ARGS="--only NAME,NAME".
.PHONY: peer
peer: setup
	@$(ROS_ENV) && python3 tools/peer/run_peer.py $(PEER_ARGS)

# make train: not part of make test. Installs the train extra on first use (stable-baselines3,
# a CPU build of torch, matplotlib: tools/install_extra.sh), then trains DQN on learning stage 1
# (tools/train_stage1.py; TRAIN_ARGS="--steps 20000" etc.); CSV, plot and model in catkin_ws/train.
.PHONY: train
train: setup
	@$(ROS_ENV) && bash tools/install_extra.sh train && python3 tools/train_stage1.py $(TRAIN_ARGS)

# make slam / make nav: not part of make test. The e-Manual's SLAM and Navigation chapters
# (make nav-extra: only the extra's build, as make test does where NAV_SRC is set)
# (doc/slam.md, doc/navigation.md). The navigation extra (gmapping, amcl, map_server, move_base)
# is built on first use (tools/install_extra.sh nav: catkin_ws/nav, once). make slam: the sim in
# turtlebot3_world, gmapping, RViz and keyboard teleop in this terminal. make nav: the sim,
# map_server with MAP (default ~/map.yaml, what map_saver -f ~/map writes), amcl started at the
# world's spawn, move_base and RViz.
NAV_ENV := if [ -f $(WS)/nav/devel/setup.bash ]; then source $(WS)/nav/devel/setup.bash; \
	else $(ROS_ENV); fi
MAP ?= $(HOME)/map.yaml
.PHONY: slam nav nav-extra
nav-extra: setup
	@bash tools/install_extra.sh nav

slam: setup
	@bash tools/install_extra.sh nav && $(NAV_ENV) && roslaunch tutorial_turtlebot \
	turtlebot3_slam.launch sim:=true teleop:=true model:=$(MODEL)

nav: setup
	@bash tools/install_extra.sh nav && $(NAV_ENV) && roslaunch tutorial_turtlebot \
	turtlebot3_navigation.launch sim:=true model:=$(MODEL) map_file:=$(MAP) \
	initial_pose_x:=-2.0 initial_pose_y:=-0.5 initial_pose_a:=0.0

clean:
	rm -rf $(WS) .catkin_ws
