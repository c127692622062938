"""A faithful equivalent, for the tests, of ROBOTIS' turtlebot3_machine_learning (ROS 1, noetic)
stage clients: ``environment_stage_N.Env`` with its ``respawnGoal.Respawn``, and the stage 3
obstacle node ``moving_obstacle.py``. Our own code, written from reading ROBOTIS' files; it
shares nothing with src/tutorial_turtlebot/learning, so that the equivalence test compares two
independent implementations.

Same as ROBOTIS: the topics and services (``cmd_vel``, ``odom``, ``scan`` read with
rospy.wait_for_message after each command, ``gazebo/reset_simulation``, ``gazebo/model_states``,
``gazebo/spawn_sdf_model`` and ``gazebo/delete_model`` of the goal model ``goal``), the heading
rounded to 0.01 in the odometry callback, the state (+inf as 3.5, NaN as 0), the collision test
0.13 > min > 0, the goal test distance < 0.2, the reward formula and the stage's collision and
goal rewards, the goals drawn with randrange as Respawn.getPosition draws them.

Differences from ROBOTIS, each needed by the test and marked ``DIFFERENCE`` where it is made:
  1. the goals come from a ``random.Random`` passed in (ROBOTIS: the module-level random), so
     that both sides draw the same goals from one seed;
  2. no time.sleep(0.5) before the goal's spawn: it only slows the run (and at a real-time
     factor below 1 it would stop the robot for several scan periods of sim time);
  3. after the scan, the step waits (at most 1 wall s) until the odometry callback has seen
     the odometry of the scan's moment: ROBOTIS reads whichever odometry came last, and over
     ROS that is the scan's moment or 1/30 s before, by a race between two threads;
  4. the busy waits on the goal model (respawnModel, deleteModel) sleep 1 ms a turn, so that
     they do not starve the subscriber threads they wait for (ROBOTIS spins on ``pass``);
  5. the obstacle node is a thread (``MovingObstacle``) that ticks once every 0.1 s of sim
     time, at fixed multiples of 0.1 s from a start time, instead of sleeping 0.1 s of wall
     time after each tick: see its docstring.
"""
import math
import threading
import time

import numpy as np
import rospy
from gazebo_msgs.msg import ModelState, ModelStates
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty

# environment_stage_N.setReward: (collision reward, goal reward)
STAGE_REWARDS = {1: (-200, 200), 2: (-150, 200), 3: (-150, 200), 4: (-500, 1000)}
WAIT_TURN = 0.001   # wall s a busy wait sleeps each turn (DIFFERENCE 4)


def yaw_of(q) -> float:
    """tf.transformations.euler_from_quaternion's yaw ('sxyz') of a geometry_msgs/Quaternion."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class Respawn:
    """respawnGoal.Respawn: the goal model, spawned and deleted through /gazebo."""

    def __init__(self, stage: int, rng, model_xml: str):
        self.model = model_xml
        self.stage = stage
        self.rng = rng                       # DIFFERENCE 1
        self.goal_position = Pose()
        self.init_goal_x, self.init_goal_y = 0.6, 0.0
        self.goal_position.position.x = self.init_goal_x
        self.goal_position.position.y = self.init_goal_y
        self.modelName = "goal"
        self.obstacles = ((0.6, 0.6), (0.6, -0.6), (-0.6, 0.6), (-0.6, -0.6), (0.0, 0.0))
        self.last_goal_x, self.last_goal_y = self.init_goal_x, self.init_goal_y
        self.last_index = 0
        self.check_model = False
        self.index = 0
        self.sub_model = rospy.Subscriber("gazebo/model_states", ModelStates, self.checkModel)

    def checkModel(self, model):
        self.check_model = "goal" in model.name

    def respawnModel(self):
        while self.check_model:
            time.sleep(WAIT_TURN)            # DIFFERENCE 4
        rospy.wait_for_service("gazebo/spawn_sdf_model")
        spawn = rospy.ServiceProxy("gazebo/spawn_sdf_model", SpawnModel)
        spawn(self.modelName, self.model, "robotos_name_space", self.goal_position, "world")
        rospy.loginfo("Goal position : %.1f, %.1f", self.goal_position.position.x,
                      self.goal_position.position.y)

    def deleteModel(self):
        while not self.check_model:
            time.sleep(WAIT_TURN)            # DIFFERENCE 4
        rospy.wait_for_service("gazebo/delete_model")
        rospy.ServiceProxy("gazebo/delete_model", DeleteModel)(self.modelName)

    def getPosition(self, position_check=False, delete=False):
        if delete:
            self.deleteModel()
        if self.stage != 4:
            while position_check:
                goal_x = self.rng.randrange(-12, 13) / 10.0
                goal_y = self.rng.randrange(-12, 13) / 10.0
                position_check = any(abs(goal_x - ox) <= 0.4 and abs(goal_y - oy) <= 0.4
                                     for ox, oy in self.obstacles)
                if abs(goal_x - self.last_goal_x) < 1 and abs(goal_y - self.last_goal_y) < 1:
                    position_check = True
                self.goal_position.position.x = goal_x
                self.goal_position.position.y = goal_y
        else:
            goal_x_list = [0.6, 1.9, 0.5, 0.2, -0.8, -1, -1.9, 0.5, 2, 0.5, 0, -0.1, -2]
            goal_y_list = [0, -0.5, -1.9, 1.5, -0.9, 1, 1.1, -1.5, 1.5, 1.8, -1, 1.6, -0.8]
            while position_check:
                self.index = self.rng.randrange(0, 13)
                if self.last_index == self.index:
                    position_check = True
                else:
                    self.last_index = self.index
                    position_check = False
                self.goal_position.position.x = goal_x_list[self.index]
                self.goal_position.position.y = goal_y_list[self.index]
        # DIFFERENCE 2: ROBOTIS sleeps 0.5 s (wall) here
        self.respawnModel()
        self.last_goal_x = self.goal_position.position.x
        self.last_goal_y = self.goal_position.position.y
        return self.goal_position.position.x, self.goal_position.position.y


class Env:
    """environment_stage_N.Env for ``stage`` 1 to 4, over ROS."""

    def __init__(self, stage: int, action_size: int, rng, goal_xml: str):
        self.stage = stage
        self.goal_x = 0
        self.goal_y = 0
        self.heading = 0
        self.action_size = action_size
        self.initGoal = True
        self.get_goalbox = False
        self.position = Pose().position
        self.odom_stamp = rospy.Time(0)      # DIFFERENCE 3
        self.last_odom = None
        self.last_goal_hit = False
        self.pub_cmd_vel = rospy.Publisher("cmd_vel", Twist, queue_size=5)
        self.sub_odom = rospy.Subscriber("odom", Odometry, self.getOdometry)
        self.reset_proxy = rospy.ServiceProxy("gazebo/reset_simulation", Empty)
        self.respawn_goal = Respawn(stage, rng, goal_xml)
        self.goal_distance = 1.0
        self.last_scan = None                # the scan of the last state, for the test

    def getGoal(self):
        return [self.goal_x, self.goal_y]

    def getGoalDistace(self):
        return round(math.hypot(self.goal_x - self.position.x, self.goal_y - self.position.y), 2)

    def getOdometry(self, odom):
        self.position = odom.pose.pose.position
        yaw = yaw_of(odom.pose.pose.orientation)
        goal_angle = math.atan2(self.goal_y - self.position.y, self.goal_x - self.position.x)
        heading = goal_angle - yaw
        if heading > math.pi:
            heading -= 2 * math.pi
        elif heading < -math.pi:
            heading += 2 * math.pi
        self.heading = round(heading, 2)
        self.odom_stamp = odom.header.stamp  # DIFFERENCE 3
        self.last_odom = odom                # for the test: the pose of the state

    def _wait_odometry_of(self, scan):
        """DIFFERENCE 3: until the callback has seen the odometry of ``scan``'s moment (the sim
        publishes odometry at 30 Hz from the same moment as the 5 Hz scan: every scan has one)."""
        # != rather than <: after reset_simulation the last odometry is stamped later
        deadline = time.monotonic() + 1.0
        while self.odom_stamp != scan.header.stamp and time.monotonic() < deadline:
            time.sleep(WAIT_TURN)

    def getState(self, scan):
        scan_range = []
        heading = self.heading
        min_range = 0.13
        done = False
        for r in scan.ranges:
            if r == float("Inf"):
                scan_range.append(3.5)
            elif np.isnan(r):
                scan_range.append(0)
            else:
                scan_range.append(r)
        obstacle_min_range = round(min(scan_range), 2)
        obstacle_angle = np.argmin(scan_range)
        if min_range > min(scan_range) > 0:
            done = True
        current_distance = round(math.hypot(self.goal_x - self.position.x,
                                            self.goal_y - self.position.y), 2)
        if current_distance < 0.2:
            self.get_goalbox = True
        if self.stage == 1:
            tail = [0, 0]
        else:
            tail = [obstacle_min_range, obstacle_angle]
        return scan_range + [heading, current_distance] + tail, done

    def setReward(self, state, done, action):
        yaw_reward = []
        obstacle_min_range = state[-2]
        current_distance = state[-3]
        heading = state[-4]
        for i in range(5):
            angle = -math.pi / 4 + heading + (math.pi / 8 * i) + math.pi / 2
            tr = 1 - 4 * math.fabs(0.5 - math.modf(0.25 + 0.5 * angle % (2 * math.pi)
                                                   / math.pi)[0])
            yaw_reward.append(tr)
        distance_rate = 2 ** (current_distance / self.goal_distance)
        if self.stage == 4:
            ob_reward = -5 if obstacle_min_range < 0.5 else 0
            reward = ((round(yaw_reward[action] * 5, 2)) * distance_rate) + ob_reward
        else:
            reward = ((round(yaw_reward[action] * 5, 2)) * distance_rate)
        collision_reward, goal_reward = STAGE_REWARDS[self.stage]
        if done:
            rospy.loginfo("Collision!!")
            reward = collision_reward
            self.pub_cmd_vel.publish(Twist())
        if self.get_goalbox:
            rospy.loginfo("Goal!!")
            reward = goal_reward
            self.pub_cmd_vel.publish(Twist())
            self.goal_x, self.goal_y = self.respawn_goal.getPosition(True, delete=True)
            self.goal_distance = self.getGoalDistace()
            self.get_goalbox = False
        return reward

    def _next_scan(self):
        data = None
        while data is None and not rospy.is_shutdown():
            try:
                data = rospy.wait_for_message("scan", LaserScan, timeout=5)
            except rospy.ROSException:
                pass
        return data

    def step(self, action):
        max_angular_vel = 1.5
        ang_vel = ((self.action_size - 1) / 2 - action) * max_angular_vel * 0.5
        vel_cmd = Twist()
        vel_cmd.linear.x = 0.15
        vel_cmd.angular.z = ang_vel
        self.pub_cmd_vel.publish(vel_cmd)
        data = self._next_scan()
        self._wait_odometry_of(data)         # DIFFERENCE 3
        self.last_scan, self.state_odom = data, self.last_odom
        state, done = self.getState(data)
        goal = self.get_goalbox              # for the test: setReward clears it
        reward = self.setReward(state, done, action)
        self.last_goal_hit = goal
        return np.asarray(state), reward, done

    def reset(self):
        rospy.wait_for_service("gazebo/reset_simulation")
        try:
            self.reset_proxy()
        except rospy.ServiceException:
            print("gazebo/reset_simulation service call failed")
        data = self._next_scan()
        self._wait_odometry_of(data)         # DIFFERENCE 3
        self.last_scan, self.state_odom = data, self.last_odom
        if self.initGoal:
            self.goal_x, self.goal_y = self.respawn_goal.getPosition()
            self.initGoal = False
        self.goal_distance = self.getGoalDistace()
        state, done = self.getState(data)
        return np.asarray(state)


class MovingObstacle(threading.Thread):
    """moving_obstacle.py (stage 3) as a thread: at each tick, read the obstacle's pose from
    /gazebo/model_states (rospy.wait_for_message) and publish it to /gazebo/set_model_state
    with angular z 0.5 rad/s.

    DIFFERENCE 5: ROBOTIS sleeps 0.1 s of wall time after each tick, so its ticks come every
    0.1 s plus the tick's own latency (a new subscription to model_states each time), a number
    of ticks per sim second that depends on the machine and the real-time factor. The obstacle
    has friction on the ground: a tick's 0.5 rad/s dies away within about 0.1 s, so the
    obstacle turns by about the same angle at every tick and its angle counts the ticks. This
    thread ticks at ``start`` + 0.1 s, + 0.2 s, ... of sim time, the moments the obstacle node
    would tick at if its latency were nothing (what the Gymnasium environment models)."""

    def __init__(self, start: rospy.Time, period: float = 0.1):
        super().__init__(daemon=True)
        self.start_time = start
        self.period = period
        self.stopping = threading.Event()
        self.ticks = []    # (sim time s it was due, obstacle yaw rad read) of each tick
        self.pub_model = rospy.Publisher("gazebo/set_model_state", ModelState, queue_size=1)

    def run(self):
        k = 1
        while not self.stopping.is_set() and not rospy.is_shutdown():
            due = self.start_time + rospy.Duration(self.period * k)
            if rospy.get_rostime() - due > rospy.Duration(self.period / 2):
                k += 1        # missed (a reset, a stall): no catching up, a tick is a tick
                continue
            while rospy.get_rostime() < due and not self.stopping.is_set():
                time.sleep(0.0005)
            if self.stopping.is_set():
                return
            try:
                model = rospy.wait_for_message("gazebo/model_states", ModelStates, timeout=5)
            except rospy.ROSException:
                continue
            for i, name in enumerate(model.name):
                if name == "obstacle":
                    obstacle = ModelState()
                    obstacle.model_name = "obstacle"
                    obstacle.pose = model.pose[i]
                    obstacle.twist = Twist()
                    obstacle.twist.angular.z = 0.5
                    self.pub_model.publish(obstacle)
                    # for the test: the tick's moment and the yaw it found (at rest by then)
                    self.ticks.append((due.to_sec(), yaw_of(model.pose[i].orientation)))
            k += 1

    def stop(self):
        self.stopping.set()
        self.join(5.0)
