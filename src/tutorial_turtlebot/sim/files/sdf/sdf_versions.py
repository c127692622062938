"""SDF files of older versions, converted as Gazebo 11 converts them before reading them. No ROS,
no pybullet.

libsdformat 9 converts a file of SDF 1.2 to 1.6, one version at a time, to SDF 1.7 (the steps
of its sdf/1.x/*.convert files, applied by its Converter.cc); ``upgraded`` applies the same
steps to the parsed tree (xml_reader) before the world loader (world_sdf) reads it:

- 1.2 -> 1.3: nothing (sdformat's step is empty);
- 1.3 -> 1.4: ``<physics>``'s ``<update_rate>`` becomes ``<real_time_update_rate>``, its
  ``<ode><solver><dt>`` (or ``<bullet><dt>``) ``<max_step_size>``;
- 1.4 -> 1.5: each axis of a joint of a world's model or a model file's model gets
  ``<use_parent_model_frame>true`` (in 1.4 an axis is in the model frame); an actor's
  ``static`` attribute becomes an element;
- 1.5 -> 1.6: ``<physics>``'s ``<gravity>`` and ``<magnetic_field>`` move to the ``<world>``;
  an IMU's ``<noise>`` (type, ``<rate>`` and ``<accel>``) is copied to each axis of its
  ``<angular_velocity>`` and ``<linear_acceleration>``;
- 1.6 -> 1.7: ``<pose frame="...">`` becomes ``relative_to``; a joint axis's
  ``<use_parent_model_frame>`` true becomes ``<xyz expressed_in="__model__">``.

Each step is applied in full: every rename and move of these files touches an element the
loader, sdf_joints or sdf_elements' table reads. A file of SDF 1.7 is read as it stands, and so
is one of a version libsdformat 9 does not convert (1.8, 2.0, or 1.0 in an ``<sdf>`` root): one
warning line, as Gazebo prints "Unable to convert" and reads it as it stands.

``<gazebo version="1.0">`` (or "1.2") files, Gazebo 1.x's, are refused by Gazebo 11 (libsdformat
8 dropped them: it reads an ``<sdf>`` root only). They are read here, with one warning line
saying so, as libsdformat 6 (Gazebo 9) read them: the root taken as ``<sdf>``, and for 1.0 its
step to 1.2 first, in full but for two parts that change nothing sdformat reads either: the
deprecation notes of a ``<scene>``'s sky, and a sensor's ``<save path>`` (its rule in the
convert file is malformed, so sdformat does nothing there). In that step an attribute becomes
the element of its name (``<box size="1 1 1"/>``, ``<model static="1">``, ``<link gravity=...>``,
``<inertial mass=...>``, ``<ode mu=... mu2=...>``, ``<axis xyz=...>`` ...), ``<origin
pose="..."/>`` becomes ``<pose>``, ``<ambient rgba="..."/>`` ``<ambient>`` (and the like for a
material's colours, a light's, ``<gravity xyz>``, a joint's ``<parent link>`` and ``<child
link>``), a fog's ``rgba`` its ``<color>``, a heightmap's ``origin`` its ``<pos>``, and a model
file's link ``<damping>`` its ``<velocity_decay>``.

Not converted, as libsdformat converts neither: a mesh's ``<filename>`` (SDF 1.2's, dropped in
1.3: Gazebo 11 reads ``<uri>`` alone; sdf_elements leaves such a mesh out with one warning), and
a 1.0 material's ``script`` name (it becomes a ``<script>`` without a ``<name>``: drawn grey).

The root's ``version`` attribute is left as the file wrote it (sdf_joints reads it); warnings
are one line each (sdf_elements.one_line), kept with the root (``version_warnings``).
"""
from dataclasses import replace
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Tuple

from .. import xml_reader
from ..xml_reader import Element
from .sdf_elements import one_line

SDF_VERSION = "1.7"       # what libsdformat 9 (Gazebo 11) reads; every file is converted to it
MODEL_FRAME = "__model__"
TRUE_WORDS = ("true", "True", "TRUE", "1")     # use_parent_model_frame values sdformat maps

Op = Callable[[Element], None]
Step = Tuple[Tuple[Op, ...], Dict[str, "Step"]]


# --- the operations of a convert file, on xml_reader Elements ---------------------------------

def _step(*ops: Op, **children: Step) -> Step:
    """A conversion of one element: ``ops`` on it, after each ``children`` step on every child
    of that tag (sdformat's <convert name=...> first, then the element's own changes)."""
    return ops, children


def _apply(elem: Element, step: Step) -> None:
    ops, children = step
    for tag, inner in children.items():
        for child in elem.findall(tag):
            _apply(child, inner)
    for op in ops:
        op(elem)


def _new(tag: str, line: int, text: Optional[str] = None) -> Element:
    node = xml_reader.element(tag, {}, line)
    node.text = text
    return node


def _clone(elem: Element, tag: str) -> Element:
    """A deep copy of ``elem`` named ``tag`` (copy.deepcopy would lose the line numbers)."""
    node = xml_reader.element(tag, elem.attrib, elem.line, [_clone(c, c.tag) for c in elem])
    node.text, node.tail = elem.text, elem.tail
    return node


def _attrs(*names: str, to: Optional[str] = None) -> Op:
    """Each attribute of ``names`` becomes a last child element of its name (or ``to``)."""
    def op(elem: Element) -> None:
        for name in names:
            value = elem.attrib.pop(name, None)
            if value is not None:
                elem.append(_new(to or name, elem.line, value))
    return op


def _from_child(child: str, attribute: str, to: str) -> Op:
    """The first child ``child``'s ``attribute`` becomes the element ``to`` in its place."""
    def op(elem: Element) -> None:
        old = elem.find(child)
        if old is not None and attribute in old.attrib:
            elem[list(elem).index(old)] = _new(to, old.line, old.attrib[attribute])
    return op


def _renamed(child: str, to: str) -> Op:
    """The first child ``child`` becomes ``to``, with its text alone (sdformat's rename)."""
    def op(elem: Element) -> None:
        old = elem.find(child)
        if old is not None and old.text is not None:
            elem[list(elem).index(old)] = _new(to, old.line, old.value)
    return op


def _made(elem: Element, path: Sequence[str]) -> Element:
    """The element at ``path`` (first children) under ``elem``, made where missing."""
    for tag in path:
        found = elem.find(tag)
        if found is None:
            found = _new(tag, elem.line)
            elem.append(found)
        elem = found
    return elem


def _moved(source: str, target: str, keep: bool = False, attribute: str = "") -> Op:
    """The element at the "::" path ``source`` moves (``keep``: is copied) to the path
    ``target``, renamed as its last part; with ``attribute``, its text becomes that attribute
    of the element at ``target`` instead. Nothing is moved without a source, but the target's
    path is made once the source's parent is found (sdformat's Move)."""
    *way, name = source.split("::")
    parts = target.split("::")

    def op(elem: Element) -> None:
        holder = elem
        for tag in way:
            holder = holder.find(tag)
            if holder is None:
                return
        destination = _made(elem, parts if attribute else parts[:-1])
        moving = holder.find(name)
        if moving is None:
            return
        if attribute:
            destination.set(attribute, moving.value)
        else:
            destination.append(_clone(moving, parts[-1]))
        if not keep:
            holder.remove(moving)
    return op


def _added(tag: str, value: Optional[str] = None) -> Op:
    return lambda elem: elem.append(_new(tag, elem.line, value))


def _removed(tag: str) -> Op:
    def op(elem: Element) -> None:
        for child in elem.findall(tag):
            elem.remove(child)
    return op


def _renamed_attribute(name: str, to: str) -> Op:
    def op(elem: Element) -> None:
        if name in elem.attrib:
            elem.set(to, elem.attrib.pop(name))
    return op


def _model_frame_axis(axis: Element) -> None:
    """1.6 -> 1.7: use_parent_model_frame true becomes <xyz expressed_in="__model__">."""
    flag = axis.find("use_parent_model_frame")
    if flag is not None and flag.value in TRUE_WORDS:
        _made(axis, ["xyz"]).set("expressed_in", MODEL_FRAME)
    _removed("use_parent_model_frame")(axis)


def _descendants(tag: str, step: Step) -> Op:
    """``step`` on every element ``tag`` below, not inside a <plugin> or a tag with a prefix
    (sdformat's descendant_name)."""
    def walk(elem: Element) -> None:
        if elem.tag == "plugin" or ":" in elem.tag:
            return
        for child in list(elem):
            if child.tag == tag:
                _apply(child, step)
            walk(child)
    return walk


# --- SDF 1.0 -> 1.2 (a <gazebo version="1.0"> file) -----------------------------------------

_ORIGIN = _from_child("origin", "pose", "pose")


def _colours(*tags: str) -> Tuple[Op, ...]:
    return tuple(_from_child(tag, "rgba", tag) for tag in tags)


_GEOMETRY_1_0 = _step(
    box=_step(_attrs("size")), sphere=_step(_attrs("radius")),
    cylinder=_step(_attrs("radius", "length")), mesh=_step(_attrs("filename", "scale")),
    image=_step(_attrs("filename", "scale", "threshold", "height", "granularity")),
    heightmap=_step(_attrs("filename", "size"), _attrs("origin", to="pos")),
    plane=_step(_attrs("normal")))
_SCAN_1_0 = _step(_attrs("samples", "resolution", "min_angle", "max_angle"))
_AXIS_1_0 = _step(_attrs("xyz"), dynamics=_step(_attrs("damping", "friction")),
                  limit=_step(_attrs("lower", "upper", "effort", "velocity")))
_CFM_ERP = _step(_attrs("cfm", "erp"))


def _link_1_0(*ops: Op) -> Step:
    return _step(
        _attrs("gravity", "self_collide", "kinematic"), *ops, _ORIGIN,
        inertial=_step(_ORIGIN, _attrs("mass", "density"), inertia=_step(
            _attrs("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))),
        sensor=_step(
            _ORIGIN, _attrs("always_on", "update_rate", "visualize"),
            ray=_step(scan=_step(horizontal=_SCAN_1_0, vertical=_SCAN_1_0),
                      range=_step(_attrs("min", "max", "resolution"))),
            camera=_step(_from_child("horizontal_fov", "angle", "horizontal_fov"),
                         image=_step(_attrs("width", "height", "format"))),
            clip=_step(_attrs("near", "far")), depth_camera=_step(_attrs("output"))),
        collision=_step(
            _ORIGIN, _attrs("laser_retro"), geometry=_GEOMETRY_1_0, surface=_step(
                bounce=_step(_attrs("restitution_coefficient", "threshold")),
                friction=_step(ode=_step(_attrs("mu", "mu2", "fdir1", "slip1", "slip2"))),
                contact=_step(ode=_step(_attrs("soft_cfm", "soft_erp", "kp", "kd", "max_vel",
                                               "min_depth"))))),
        visual=_step(
            _ORIGIN, _attrs("cast_shadows", "laser_retro", "transparency"),
            geometry=_GEOMETRY_1_0,
            material=_step(_attrs("script"),
                           *_colours("ambient", "specular", "diffuse", "emissive"))))


def _model_1_0(link: Step) -> Step:
    return _step(
        _ORIGIN, _attrs("static"), link=link,
        gripper=_step(grasp_check=_step(
            _attrs("detach_steps", "attach_steps", "min_contact_count"))),
        joint=_step(_ORIGIN, _from_child("parent", "link", "parent"),
                    _from_child("child", "link", "child"), axis=_AXIS_1_0, axis2=_AXIS_1_0,
                    physics=_step(limit=_CFM_ERP, suspension=_CFM_ERP)))


_TO_1_2 = _step(
    world=_step(
        state=_step(_attrs("time")),
        physics=_step(_attrs("update_rate"), _from_child("gravity", "xyz", "gravity"), ode=_step(
            solver=_step(_attrs("type", "dt", "iters", "precon_iters", "sor")),
            constraints=_step(_attrs("cfm", "erp", "contact_max_correcting_vel",
                                     "contact_surface_layer")))),
        gui=_step(camera=_step(_ORIGIN)),
        scene=_step(*_colours("ambient", "background"),
                    _from_child("shadows", "enabled", "shadows"),
                    _from_child("grid", "enabled", "grid"),
                    fog=_step(_attrs("rgba", to="color"),
                              _attrs("type", "start", "end", "density"))),
        actor=_step(
            _ORIGIN, skin=_step(_attrs("filename", "scale")),
            animation=_step(_attrs("filename", "scale", "interpolate_x")),
            script=_step(_attrs("loop", "delay_start", "auto_start"), trajectory=_step(
                waypoint=_step(_attrs("time", "pose"))))),
        light=_step(
            _ORIGIN, _attrs("cast_shadows"), *_colours("diffuse", "specular"),
            _from_child("direction", "xyz", "direction"),
            spot=_step(_attrs("inner_angle", "outer_angle", "falloff")),
            attenuation=_step(_attrs("range", "linear", "constant", "quadratic"))),
        model=_model_1_0(_link_1_0())),
    model=_model_1_0(_link_1_0(_renamed("damping", "velocity_decay"))))


# --- SDF 1.3 -> 1.4 -> 1.5 -> 1.6 -> 1.7 ------------------------------------------------------

_TO_1_4 = _step(world=_step(physics=_step(
    _moved("update_rate", "real_time_update_rate"), _moved("ode::solver::dt", "max_step_size"),
    _moved("bullet::dt", "max_step_size"))))

_JOINT_1_4 = _step(axis=_step(_added("use_parent_model_frame", "true")),
                   axis2=_step(_added("use_parent_model_frame", "true")))
_TO_1_5 = _step(world=_step(model=_step(joint=_JOINT_1_4), actor=_step(_attrs("static"))),
                model=_step(joint=_JOINT_1_4, actor=_step(_attrs("static"))))


def _imu_noise_1_5() -> Tuple[Op, ...]:
    """1.5 -> 1.6: an IMU's one <noise> copied to each axis of its two new groups."""
    ops: List[Op] = [_added("angular_velocity"), _added("linear_acceleration")]
    for group in ("angular_velocity", "linear_acceleration"):
        ops += [_moved("noise::type", "%s::%s::noise" % (group, axis), keep=True,
                       attribute="type") for axis in "xyz"]
    for group, source in (("angular_velocity", "rate"), ("linear_acceleration", "accel")):
        for field in ("mean", "stddev", "bias_mean", "bias_stddev"):
            ops += [_moved("noise::%s::%s" % (source, field),
                           "%s::%s::noise::%s" % (group, axis, field), keep=True)
                    for axis in "xyz"]
    return tuple(ops) + (_removed("noise"),)


_IMU_1_5 = _step(sensor=_step(imu=_step(*_imu_noise_1_5())))
_TO_1_6 = _step(
    world=_step(_moved("physics::gravity", "gravity"),
                _moved("physics::magnetic_field", "magnetic_field"),
                model=_step(link=_IMU_1_5)),
    model=_step(link=_IMU_1_5))

_TO_1_7 = _step(
    _descendants("pose", _step(_renamed_attribute("frame", "relative_to"))),
    _descendants("joint", _step(axis=_step(_model_frame_axis),
                                axis2=_step(_model_frame_axis))))

# (from, to, step): libsdformat 9 starts at a file's version among the first ones (1.0 only in
# a <gazebo> root: see the module's docstring)
STEPS: Tuple[Tuple[str, str, Optional[Step]], ...] = (
    ("1.0", "1.2", _TO_1_2), ("1.2", "1.3", None), ("1.3", "1.4", _TO_1_4),
    ("1.4", "1.5", _TO_1_5), ("1.5", "1.6", _TO_1_6), ("1.6", "1.7", _TO_1_7))
GAZEBO_ROOT = ('<gazebo version="%s">: Gazebo 11 refuses this file (libsdformat 9 reads an '
               '<sdf> root only); read here converted, as Gazebo 9 (libsdformat 6) read it')
UNKNOWN = ('<%s version="%s">: not a version Gazebo 11 converts (1.2 to 1.7): read as it '
           'stands, as Gazebo reads it ("Unable to convert from SDF version %s to 1.7")')


def upgraded(root: Element, source: str) -> Element:
    """``root`` (a parsed SDF file or text, named ``source`` in warnings) converted in place to
    SDF 1.7 as libsdformat 9 converts it, once; a ``<gazebo>`` root with a version is read as
    libsdformat 6 read it (renamed ``<sdf>``). Its warnings: ``version_warnings``."""
    if getattr(root, "version_notes", None) is not None:
        return root
    version, tag = root.attrib.get("version"), root.tag
    notes = []
    steps = STEPS[1:] if root.tag == "sdf" else STEPS
    if root.tag == "gazebo" and version is not None:
        notes.append(one_line(source, root.line, GAZEBO_ROOT % version))
        root.tag = "sdf"
    elif root.tag != "sdf" or version is None or version == SDF_VERSION:
        steps = ()
    if steps and version not in [first for first, _, _ in steps] + [SDF_VERSION]:
        notes.append(one_line(source, root.line, UNKNOWN % (tag, version, version)))
    started = False
    for first, _, step in steps:
        started = started or first == version
        if started and step is not None:
            _apply(root, step)
    root.version_notes = tuple(notes)
    return root


def version_warnings(root: Element) -> Tuple[str, ...]:
    """The warning lines ``upgraded`` noted for ``root`` (none for another element)."""
    return getattr(root, "version_notes", ())


def with_version_warnings(world, roots: Iterable[Element]):
    """``world`` (a world_types.World) with the version warnings of ``roots`` (its file's root
    and those of the files it includes) before its own, each once."""
    notes: List[str] = []
    for root in roots:
        notes += [n for n in version_warnings(root) if n not in notes + list(world.warnings)]
    return replace(world, warnings=tuple(notes) + tuple(world.warnings)) if notes else world
