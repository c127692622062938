"""The SDF elements Gazebo 11 reads, and what this simulator does with each: the rule the world
loader (world_sdf) follows and doc/worlds.md's table shows. No ROS, no pybullet.

Each element is ``simulated`` (as Gazebo does), ``approximated`` (loaded, with a difference the
doc names, and no warning) or ``skipped`` (left out with one warning line per kind and world).
None of them refuses a world: a refusal is kept for what Gazebo refuses too or what would
poison the physics (a NaN pose, an include loop, the bounds of ``limits``). An element that
Gazebo 11 does not read either (sdformat 9 copies it aside, readXml) is passed over in silence.

A few elements are simulated only at their default value (a link's ``<gravity>`` true,
``<kinematic>`` false): another value is the one warning, and in a static model none.
"""
import math
import os
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Tuple

from ..plugins.sensor_reader import plugin_file
from ..plugins.table import is_model_plugin
from ..xml_reader import Element, boolean, numbers

SIMULATED, APPROXIMATED, SKIPPED = "simulated", "approximated", "skipped"
MAX_WARNING_CHARS = 200      # a warning line is at most this long (the file named by its base)


@dataclass(frozen=True)
class Rule:
    """What is done with one element: ``mark`` and, in words, ``here``. ``simulated_if`` (the
    element, whether its model is static) says whether this value is one the sim simulates;
    when it says no, the element is skipped with one warning (``why``)."""

    mark: str
    here: str
    simulated_if: Optional[Callable[[Element, bool], bool]] = None
    why: str = ""            # the warning's words when ``simulated_if`` says no (else ``here``)


def _is_bool(default: bool) -> Callable[[Element, bool], bool]:
    """True for ``default`` (or no value), and in a static model, where nothing moves."""
    def check(node: Element, static: bool) -> bool:
        if static:
            return True
        try:
            return boolean(node.value) == default if node.value else True
        except ValueError:
            return True          # not a bool: Gazebo keeps its default too
    return check


def _no_decay(node: Element, static: bool) -> bool:
    if static:
        return True
    for tag in ("linear", "angular"):
        child = node.child(tag)
        if child is not None and child.value:
            value = numbers(child.value, 1, finite=False)
            if value is not None and not (math.isnan(value[0]) or value[0] == 0.0):
                return False
    return True


def _names_a_uri(node: Element, static: bool) -> bool:
    """False for a <mesh> naming its file in SDF 1.2's <filename> alone, with no <uri>."""
    return node.child("uri") is not None or node.child("filename") is None


def _rule(mark: str, here: str, simulated_if=None, why: str = "") -> Rule:
    return Rule(mark, here, simulated_if, why)


S, A, K = SIMULATED, APPROXIMATED, SKIPPED
NO_PLUGINS = "plugins do not run here (the sim offers gazebo_ros' world API itself)"


def _runs_here(node: Element, static: bool) -> bool:
    """A model <plugin> that runs on world models here (plugins.table)."""
    return is_model_plugin(plugin_file(node.get("filename", "") or "-"), "world")


# parent element -> child element -> Rule. The order is doc/worlds.md's.
TABLE: Dict[str, Dict[str, Rule]] = {
    "world": {
        "model": _rule(S, "built: links, collisions, visuals, a movable model's inertia; a "
                          "second of one name left out, as Gazebo leaves it out"),
        "include": _rule(S, "model://, package://, file:// and paths; <name>, <pose>, <static>; "
                            "a model, an actor or a light file"),
        "actor": _rule(A, "moved along its <script>; drawn unskinned (see Actors)"),
        "light": _rule(A, "kept for the world API; cameras have their own light"),
        "state": _rule(A, "the first <state>'s model poses; not its link poses or sim time"),
        "frame": _rule(S, "a named frame: poses can be relative_to it"),
        "physics": _rule(A, "Bullet at the node's ~max_step_size; <physics> values not read"),
        "scene": _rule(A, "cameras draw their own sky and light: no shadows, fog or grid"),
        "gui": _rule(A, "no Gazebo client; gui:=true opens pybullet's window at the robot"),
        "gravity": _rule(S, "applied, as set_physics_properties applies it"),
        "magnetic_field": _rule(A, "no magnetometer here reads it"),
        "atmosphere": _rule(A, "no altimeter or air pressure sensor here reads it"),
        "spherical_coordinates": _rule(A, "no GPS here reads it"),
        "wind": _rule(A, "nothing here feels wind (a link's <enable_wind> is a warning)"),
        "audio": _rule(A, "no sound"),
        "plugin": _rule(K, "world " + NO_PLUGINS),
        "joint": _rule(K, "a joint between world models is not simulated"),
        "road": _rule(K, "roads are not drawn (Gazebo draws them, with no collision)"),
        "population": _rule(K, "the population's copies of its model are not placed"),
    },
    "model": {
        "link": _rule(S, "built"),
        "model": _rule(S, "nested models, their names scoped model::inner::link"),
        "include": _rule(S, "as in a world"),
        "static": _rule(S, "a static model never moves; a movable one is rigid bodies"),
        "pose": _rule(S, "relative to the parent, or to a frame named in relative_to"),
        "frame": _rule(S, "a named frame: poses can be relative_to it"),
        "joint": _rule(S, "simulated in a movable model: revolute, continuous, prismatic, "
                          "fixed, ball, universal and revolute2 (two revolute axes), screw "
                          "and gearbox held fixed; to world anchors the model (see Joints)"),
        "plugin": _rule(A, "gazebo_ros_p3d, gazebo_ros_joint_state_publisher and hector's imu "
                           "and gps run (see Gazebo plugins in gazebo_node.md); other model "
                           "plugins are skipped", _runs_here, "model " + NO_PLUGINS),
        "gripper": _rule(K, "not simulated"),
        "self_collide": _rule(A, "Bullet's default"),
        "allow_auto_disable": _rule(A, "Bullet puts resting bodies to sleep itself"),
        "enable_wind": _rule(S, "false as here; true is one warning", _is_bool(False),
                             "not applied: nothing here feels wind"),
    },
    "link": {
        "collision": _rule(S, "built (a movable mesh as its convex hull)"),
        "visual": _rule(S, "drawn (see Textures and materials)"),
        "inertial": _rule(S, "a movable link's mass and inertia (one not positive definite: "
                          "1 kg m^2 a moment, as ODE takes it); a static one's unused"),
        "pose": _rule(S, "relative to the model, or to a frame named in relative_to"),
        "sensor": _rule(S, "ray, gpu_ray, camera, depth, multicamera, contact and imu sensors "
                           "run with gazebo_ros_laser, gpu_laser, range, block_laser, camera, "
                           "triggered_camera, depth_camera, multicamera, bumper or imu_sensor "
                           "(see Sensors of world models); other sensors and plugins are one "
                           "warning per kind"),
        "projector": _rule(K, "not drawn"),
        "light": _rule(K, "a link's light is not kept (the world's are)"),
        "audio_source": _rule(A, "no sound"),
        "audio_sink": _rule(A, "no sound"),
        "battery": _rule(A, "nothing drains it"),
        "self_collide": _rule(A, "Bullet's default"),
        "must_be_base_link": _rule(A, "links are separate bodies"),
        "gravity": _rule(S, "true as here; false is one warning", _is_bool(True),
                         "not applied: gravity acts on every movable link"),
        "kinematic": _rule(S, "false as here; true is one warning", _is_bool(False),
                           "not applied: the link moves as a dynamic body"),
        "velocity_decay": _rule(S, "0 as here; another value is one warning", _no_decay,
                                "not applied: no velocity decay here"),
        "enable_wind": _rule(S, "false as here; true is one warning", _is_bool(False),
                             "not applied: nothing here feels wind"),
    },
    "collision": {
        "geometry": _rule(S, "see the geometry rows"),
        "pose": _rule(S, "relative to the link, or to a frame named in relative_to"),
        "surface": _rule(A, "its friction's mu is used (below 0: friction that never gives, "
                            "as Gazebo takes it); the rest is Bullet's default"),
        "laser_retro": _rule(A, "the laser reports no retro-reflection"),
        "max_contacts": _rule(A, "Bullet's own contact count"),
    },
    "visual": {
        "geometry": _rule(S, "see the geometry rows"),
        "pose": _rule(S, "relative to the link, or to a frame named in relative_to"),
        "material": _rule(A, "colours and textures as Textures and materials says"),
        "cast_shadows": _rule(A, "no shadows are drawn"),
        "transparency": _rule(A, "drawn opaque"),
        "laser_retro": _rule(A, "the laser reports no retro-reflection"),
        "visibility_flags": _rule(A, "every camera sees every visual"),
        "meta": _rule(A, "layers are not used"),
        "plugin": _rule(K, "visual " + NO_PLUGINS),
    },
    "geometry": {
        "box": _rule(S, "built; a side of 0 is 0.1 mm (one warning per file)"),
        "cylinder": _rule(S, "built"),
        "sphere": _rule(S, "built"),
        "plane": _rule(S, "an infinite plane, as in Gazebo (its <size> only drawn); refused "
                          "in a model that is not <static>"),
        "polyline": _rule(S, "one extruded polygon"),
        "mesh": _rule(S, "Collada, STL, OBJ (see meshes); one naming its file in SDF 1.2's "
                         "<filename> alone is one warning", _names_a_uri,
                      "its file is named in SDF 1.2's <filename>, which Gazebo 11 does not "
                      "read (\"No mesh specified\"): name it in <uri>"),
        "empty": _rule(S, "nothing is built"),
        "heightmap": _rule(K, "the heightmap (a DEM file too) is left out of its link"),
        "image": _rule(K, "the image shape is left out of its link"),
    },
    "mesh": {
        "uri": _rule(S, "found as Gazebo finds it; a Fuel URL in the Fuel cache, else in a "
                        "model folder of its name (never downloaded; else left out)"),
        "scale": _rule(S, "applied; a factor 0 leaves the mesh out (no extent to draw or "
                       "hit)"),
        "submesh": _rule(S, "the named submesh alone (a Collada node's, an OBJ object's or "
                            "group's), drawn and colliding; <center> true centres it"),
    },
    "actor": {
        "pose": _rule(S, "where it stands until its script moves it"),
        "script": _rule(S, "loop, delay_start, auto_start, trajectories and waypoints"),
        "skin": _rule(A, "drawn in the pose its file is written in, if the file has "
                         "triangles; else a 0.5 x 0.5 x 1.8 m box"),
        "animation": _rule(A, "not played (no skinning)"),
        "link": _rule(A, "its visuals move with the actor; its collisions stay off, as in "
                         "Gazebo"),
        "joint": _rule(A, "not simulated"),
        "plugin": _rule(K, "actor " + NO_PLUGINS + ": the actor follows its <script>"),
    },
}


def one_line(source: str, line: int, message: str) -> str:
    """"source:line: message", at most MAX_WARNING_CHARS characters: the file named by its base
    name if the whole path makes it longer, the message cut short after that."""
    text = "%s:%d: %s" % (source, line, message)
    if len(text) > MAX_WARNING_CHARS:
        text = "%s:%d: %s" % (os.path.basename(source), line, message)
    if len(text) > MAX_WARNING_CHARS:
        text = text[:MAX_WARNING_CHARS - 3] + "..."
    return text


class ElementNotes:
    """The warnings of one world's skipped elements: one line per kind (a TABLE row), naming
    the first one's file and line, and how many more there are. Shared by the loaders of a
    world and of its includes."""

    def __init__(self, warnings: List[str]):
        self.warnings = warnings
        self._first: Dict[Tuple[str, str], List[int]] = {}   # row -> [warning index, count]

    def check(self, parent: str, node: Element, source: str, static: bool = False) -> bool:
        """Note ``node``, a child of a ``parent`` element (a TABLE key), read from ``source``.
        True if it is skipped here (the caller leaves it out), else False."""
        rule = TABLE.get(parent, {}).get(node.tag)
        if rule is None:
            return False
        if rule.mark == SKIPPED or (rule.simulated_if is not None
                                    and not rule.simulated_if(node, static)):
            self.skip(parent, node, source, rule.why or rule.here)
            return True
        return False

    def skip(self, parent: str, node: Element, source: str, why: str) -> None:
        """One warning for the kind (``parent``, ``node.tag``); later ones are counted."""
        key = (parent, node.tag)
        seen = self._first.get(key)
        if seen is not None:
            seen[1] += 1
            return
        self._first[key] = [len(self.warnings), 0]
        where = "" if parent in ("world", "geometry", "mesh") else " of %s %s" % (
            "an" if parent[0] in "aeiou" else "a", parent)
        self.warnings.append(one_line(source, node.line, "<%s>%s skipped: %s"
                                      % (node.tag, where, why)))

    def finish(self) -> None:
        """Say in each kind's line how many more of that kind the world has."""
        for index, more in self._first.values():
            if more:
                line = self.warnings[index]
                tail = " (and %d more)" % more
                if len(line) + len(tail) > MAX_WARNING_CHARS:
                    line = line[:MAX_WARNING_CHARS - len(tail) - 3] + "..."
                self.warnings[index] = line + tail
        self._first.clear()
