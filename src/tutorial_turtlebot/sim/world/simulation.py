"""The simulated world and its robots, as Gazebo and its ROS plugins present them, without ROS.

``Simulation`` owns the world's physics, the sim clock (integer ns), the world's models and the
robots (``SimRobot``, each made from its URDF's <gazebo> plugins), and answers "what is due now".
The ROS node only converts. The robot of ``SimConfig`` (the one sim.launch starts, in the
node's namespace) is ``self.robot``; others are added by ``add_robot`` (spawn_urdf_model).
Units: m, s, rad.
"""
import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

from ...errors import RequestError, UserError
from ..files import limits
from ..engine.applied_forces import AppliedForces
from ..kinematics import quat_from_yaw
from ..engine.physics import GRAVITY, WorldPhysics
from .physics_properties import OdeConfig, PhysicsProperties, bullet_parameters
from ...robot_models import model_limits, turtlebot3_model_of
from .schedule import RateSchedule, seconds_to_ns, NS_PER_S
from .sim_robot import ImuState, OdomState, RobotOptions, SimRobot, normalize_namespace
from .spawn_check import landed_pose, model_of_body, overlap_warning
from ..files.urdf.urdf_file import RobotDescription, read_urdf, urdf_path
from .actors import actor_motions
from .model_plugins import MODEL_PLUGINS, ModelPlugins
from .world_sensors import WORLD_SENSORS, WorldSensors
from ..files.plugins.robot_plugin_types import CameraSensor
from .world_models import (ENTITY_EXISTS, ModelRegistry, RobotModel, models_of_world,
                           robot_model_name, spawn_failure, spawn_refusal, urdf_model)
from ..engine import gui_window
from ..files.sdf.world_catalogue import WORLD_SUFFIXES, resolve_world
from ..files.sdf.world_sdf import load_world

__all__ = ["SimConfig", "Simulation", "OdomState", "ImuState"]
# A robot's outputs in what step() returns: (the SimRobot, "odom"); the world's: (None, "clock").
Due = Tuple[Optional[SimRobot], str]


@dataclass
class SimConfig:
    """Everything that picks what is simulated. Rates in Hz of sim time."""

    model: str = "burger"
    world: str = "turtlebot3_world"      # a catalogue name or a path to an SDF file
    x: Optional[float] = None            # spawn of base_footprint; None = the world's spawn
    y: Optional[float] = None
    z: float = 0.0
    yaw: Optional[float] = None
    # camera: None: the URDF's camera, if it has one; False: none; True on a burger: the
    # AutoRace burger's URDF
    camera: Optional[bool] = None
    lidar_model: str = "gazebo"          # gazebo: as the URDF declares; lds01: the real driver
    odom_source: Optional[str] = None    # None: the URDF's odometrySource
    clamp_cmd_vel: bool = True           # hold commands to the model's limits, as the firmware
    gui: bool = False                    # pybullet's own window (needs a display)
    time_step: float = 0.0025            # s of sim time per physics step
    solver_iterations: int = 20
    clock_rate: float = 100.0
    seed: int = 0                        # laser noise
    robot_name: Optional[str] = None     # the robot's model name; None = turtlebot3_gazebo's
    lidar_samples: Optional[int] = None  # rays per scan; None: the URDF's (the DQN stages: 24)
    spawn_robot: bool = True             # False: an empty world; robots come by spawn_model
    urdf: Optional[str] = None           # a robot URDF file to simulate instead of the model's

    def validate(self) -> None:
        """Raise UserError (one line) for any value that cannot be simulated."""
        self.robot_options().validate()
        if not 0.0001 <= self.time_step <= 0.01:
            raise UserError("max_step_size %r s is outside 0.0001..0.01" % self.time_step)
        rate = self.clock_rate
        if not (isinstance(rate, (int, float)) and 0 < rate <= 1.0 / self.time_step):
            raise UserError("clock_rate %r Hz must be > 0 and at most the physics rate %g Hz"
                            % (rate, 1.0 / self.time_step))
        for name in ("x", "y", "z", "yaw"):
            value = getattr(self, name)
            if value is not None and not (isinstance(value, (int, float))
                                          and math.isfinite(value)):
                raise UserError("spawn %s must be a finite number, got %r" % (name, value))
            problem = value is not None and limits.outside(
                "spawn " + name, value, -limits.MAX_POSITION, limits.MAX_POSITION,
                "rad" if name == "yaw" else "m")
            if problem:
                raise UserError(problem)
        if self.robot_name is not None and (not self.robot_name.strip() or "::" in self.robot_name):
            raise UserError("robot_name %r must be non-empty and without '::'" % self.robot_name)
        if not (isinstance(self.solver_iterations, int)
                and 0 < self.solver_iterations <= limits.MAX_SOLVER_ITERATIONS):
            raise UserError("solver_iterations must be a positive integer, at most %d, got %r"
                            % (limits.MAX_SOLVER_ITERATIONS, self.solver_iterations))

    def robot_options(self, urdf_robot_name: str = "") -> RobotOptions:
        """The launch args' overrides for a robot; its command limits are its TurtleBot3
        model's (the config's model, else the one its URDF's robot name names)."""
        model = turtlebot3_model_of(urdf_robot_name) if urdf_robot_name else self.model
        return RobotOptions(
            lidar_model=self.lidar_model, lidar_samples=self.lidar_samples,
            odom_source=self.odom_source, camera=self.camera is not False,
            limits=model_limits(model) if self.clamp_cmd_vel and model else None)


class Simulation:
    """A world with its robots, stepped one physics step at a time."""

    def __init__(self, config: SimConfig):
        config.validate()
        self.config = config
        world_path, world_spawn = resolve_world(config.world)
        self.world = load_world(world_path)
        self.spawn = self._spawn(world_spawn)
        description = None
        options = config.robot_options()
        if config.spawn_robot:
            description = read_urdf(config.urdf or urdf_path(config.model, bool(config.camera)))
        # Cameras render through EGL where it works; it must be loaded before any body. An
        # empty world (robots to be spawned) loads it in case one of them has a camera.
        wants_camera = (description is None or any(isinstance(s, CameraSensor)   # a world's too
                                                   for s in self.world.sensors
                                                   + description.plugins.sensors)
                        or (description.plugins.camera is not None and options.camera))
        self.physics = WorldPhysics(self.world, config.time_step, config.solver_iterations,
                                    config.gui, egl=wants_camera)
        self.physics_properties = PhysicsProperties.for_factor(
            config.time_step, 1.0, OdeConfig(sor_pgs_iters=config.solver_iterations),
            self.world.gravity)
        if self.world.gravity != (0.0, 0.0, -GRAVITY):    # the world file's <gravity>
            self.physics.set_gravity(self.world.gravity)
        # the world API's wrenches, joint efforts and weightless links (world_control)
        self.forces = AppliedForces(self.physics.client, lambda: self.physics_properties.gravity)
        # a rebuilt model's bodies are new: what the world API applied to the old ones goes
        self.models = ModelRegistry(on_rebuild=self.forces.forget_model)
        for model in models_of_world(self.world, self.physics.world_bodies, self.physics.client):
            self.models.add(model)
        self.actors = actor_motions(self.world, self.models)   # moved by their scripts
        self.robots: Dict[str, SimRobot] = {}
        # the world models' sensors (spawned ones too; the robots' that SimRobot does not
        # make), each at its rate: world_sensors
        self.world_sensors = WorldSensors(self.physics, self.models, config.seed, self.robots)
        self.step_ns = seconds_to_ns(config.time_step)
        self.time_ns = 0
        self.schedules: Dict[str, RateSchedule] = {"clock": RateSchedule(config.clock_rate)}
        self._robot_list: List[SimRobot] = []
        # the models' and robots' model plugins (p3d, joint states, hector's): model_plugins
        self.model_plugins = ModelPlugins(lambda: self.config.time_step, self.models,
                                          self.robots, config.seed,
                                          lambda: self.physics_properties.gravity)
        self.robot: Optional[SimRobot] = None
        self.robot_name = config.robot_name or robot_model_name(
            config.world if not config.world.endswith(WORLD_SUFFIXES) else "", config.model)
        if description is not None:   # on the floor under it (spawn_check.landed_pose)
            x, y, z, yaw = self.spawn
            pose = landed_pose(self.physics, description, ((x, y, z), quat_from_yaw(yaw)))
            self.spawn = (x, y, pose[0][2], yaw)
            self.robot = self.add_robot(self.robot_name, "", description, pose, options)
        if config.gui:
            gui_window.look_at(self.physics.client, self.spawn[:3], self.spawn[3])
        self._reset_schedules()
        self._start: Optional[Tuple[int, tuple]] = None   # (saved state, models' layout)
        self._keep_start()

    def _keep_start(self) -> None:
        """Save the physics as it stands, with no contact, as what resets go back to."""
        self.physics.renew_contacts()
        if self._start is not None:
            self.physics.drop_state(self._start[0])
        self._start = (self.physics.save_state(), self._layout())

    def _layout(self) -> tuple:
        """The bodies of the physics and of each model: a saved state fits while this is
        unchanged (no body added, removed or parked since)."""
        return self.physics.body_ids(), self.models.layout()

    def _spawn(self, world_spawn) -> Tuple[float, float, float, float]:
        default = world_spawn if world_spawn else (0.0, 0.0, 0.0)
        x, y, yaw = (default[i] if value is None else value
                     for i, value in enumerate((self.config.x, self.config.y, self.config.yaw)))
        return (x, y, self.config.z, yaw)

    def _reset_schedules(self) -> None:
        for schedule in self.schedules.values():
            schedule.reset(self.time_ns)
        self.world_sensors.reset(self.time_ns)
        self.model_plugins.reset(self.time_ns)
        self._next_output_ns = self.time_ns

    # --- robots ------------------------------------------------------------------------------

    def add_robot(self, name: str, namespace: str, description: RobotDescription, pose,
                  options: Optional[RobotOptions] = None) -> SimRobot:
        """Add a robot made from ``description``'s plugins, its root link at world ``pose``
        ((x, y, z), (qx, qy, qz, qw); on top of the floor under it if z is below that floor:
        spawn_check.landed_pose), its topics and frames in ``namespace``. RequestError
        (Gazebo's status text) when the name or namespace is taken or illegal, or the robot
        cannot be built; nothing changes then."""
        if name in self.models:
            raise RequestError(ENTITY_EXISTS)
        with spawn_refusal():
            namespace = normalize_namespace(namespace)
        for other in self._robot_list:
            if other.namespace == namespace:
                raise spawn_failure("robot %r already uses namespace %r; give this one its own "
                                    "robot_namespace" % (other.name, namespace or "/"))
        if options is None:
            options = self.config.robot_options(description.name)
        with spawn_refusal():   # on the floor under it; an overlap is one warning, as Gazebo
            pose = landed_pose(self.physics, description, pose)
            robot = SimRobot(self.physics, name, namespace, description, pose, options,
                             self.time_ns, seed=self.config.seed + len(self.robots))
        try:
            model = urdf_model(RobotModel, name, robot.body,
                               collisions=description.collision_names(), robot_body=robot.body)
            overlap = overlap_warning(self.physics, robot.body.robot, description, pose,
                                      model_of_body(self.models))
        except BaseException:   # nothing of it stays in the world
            robot.body.remove()
            raise
        if overlap is not None:
            robot.warnings.append(overlap)
        self.models.add(model)
        self.robots[name] = robot
        self._robot_list.append(robot)
        self._next_output_ns = self.time_ns
        return robot

    def remove_model(self, name: str) -> None:
        """Take model ``name`` out of the world (delete_model), and its robot, if it is one,
        out of the stepping; KeyError if there is none."""
        self.models.remove(name)
        robot = self.robots.pop(name, None)
        if robot is not None:
            self._robot_list.remove(robot)
            if robot is self.robot:
                self.robot = None

    # --- time and stepping ---------------------------------------------------------------------

    @property
    def time(self) -> float:
        """Sim time in seconds."""
        return self.time_ns / NS_PER_S

    def step(self) -> List[Due]:
        """One physics step; returns what is due at the new time: (None, "clock") and the other
        world outputs first, then (robot, "odom" | "joint_states" | "scan" | "imu" | "camera")."""
        now = self.time_ns
        for robot in self._robot_list:
            robot.before_step(now)
        if self.forces.active:
            self.forces.apply(now)
        self.physics.step()
        self.time_ns = now = now + self.step_ns
        for actor in self.actors:
            actor.update(now)
        if now < self._next_output_ns:
            return []
        due: List[Due] = [(None, name) for name, s in self.schedules.items() if s.due(now)]
        next_ns = min(s.next_ns for s in self.schedules.values())
        if self.world_sensors.due(now):   # (None, "world_sensors"): world_sensors.due_now
            due.append((None, WORLD_SENSORS))
        next_ns = min(next_ns, self.world_sensors.next_ns)
        if self.model_plugins.due(now):   # (None, "model_plugins"): model_plugins.due_now
            due.append((None, MODEL_PLUGINS))
        next_ns = min(next_ns, self.model_plugins.next_ns)
        for robot in self._robot_list:
            due.extend((robot, name) for name in robot.due(now))
            next_ns = min(next_ns, robot.next_output_ns)
        self._next_output_ns = next_ns
        return due

    def advance(self, steps: int) -> None:
        """``steps`` physics steps with each robot's drive and the world API's forces, and no
        outputs: for a client that reads the state itself when it wants it (the learning
        environments), at the cost of the physics alone. A step() afterwards reports what fell
        due meanwhile once. The same physics as ``steps`` step() calls, bit for bit: between
        two control ticks of the robots' drives (and with no forces applied) nothing but
        physics happens, so those steps run in a tight loop."""
        now, step_ns = self.time_ns, self.step_ns
        robots, forces, physics_step = self._robot_list, self.forces, self.physics.step
        actors = self.actors
        done = 0
        while done < steps:
            for robot in robots:
                robot.before_step(now)
            if forces.active:
                forces.apply(now)
                free = 0
            elif actors:   # an actor's frame may fall due at any step (actors.ActorMotion)
                free = 0
            else:   # the steps before any drive is due: before_step would do nothing
                next_ns = min([robot.next_tick_ns() for robot in robots], default=math.inf)
                free = (min(steps - done - 1, -((now + step_ns - next_ns) // step_ns))
                        if next_ns != math.inf else steps - done - 1)
            physics_step()
            now += step_ns
            for actor in actors:
                actor.update(now)
            if free > 0:
                for _ in range(free):
                    physics_step()
                now += free * step_ns
                done += free
            done += 1
        self.time_ns = now
        for robot in robots:
            robot.time_ns = now

    def reset_world(self) -> None:
        """Every model (robots, the world's movable models, spawned ones) back to its spawn
        pose at rest; time runs on (Gazebo's reset_world).

        Exact: the same commands then give the same trajectory, to the last bit, as a world
        built anew with the same models. The physics goes back to the state saved when the
        world was built, contacts and all (WorldPhysics.restore_state); after a spawn, a delete
        or a rebuild since then, every model is put at its spawn pose instead, every contact
        dropped, and that state saved for the next resets."""
        self.models.repair()
        if self._start is not None and self._start[1] == self._layout():
            self.physics.restore_state(self._start[0])
            self.models.restarted()
        else:
            self.models.reset()
            self._keep_start()
        for robot in self._robot_list:
            robot.reset_state(self.time_ns)
        self._reset_schedules()
        for actor in self.actors:    # each script starts again (Gazebo's Actor::Reset)
            actor.restart(self.time_ns)

    def reset_simulation(self) -> None:
        """Everything back to its spawn and sim time back to 0 (Gazebo's reset_simulation)."""
        self.time_ns = 0
        self.reset_world()

    def add_schedule(self, name: str, rate: float) -> None:
        """Report (None, ``name``) from step() at ``rate`` Hz of sim time from now on."""
        self.schedules[name] = RateSchedule(rate)
        self.schedules[name].reset(self.time_ns)
        self._next_output_ns = self.time_ns

    def set_physics_properties(self, props: PhysicsProperties) -> None:
        """Apply a validated PhysicsProperties: the step, gravity and Bullet's counterparts of
        the ODE fields; the real-time factor is the caller's pacer's."""
        self.physics.set_parameters(props.time_step, props.gravity, bullet_parameters(props.ode))
        self.config.time_step = props.time_step
        self.step_ns = seconds_to_ns(props.time_step)
        self.physics_properties = props

    def close(self) -> None:
        """Release the physics client."""
        self._start = None
        self.physics.close()
