"""The shipped URDF files against doc/turtlebot3.md sections 1, 2.4 and 4.5, and the URDF reader's
errors. No ROS master needed. Units: m, kg, kg*m^2, rad; poses are child-in-parent."""
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import ModelError, UrdfError
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path

ZERO = (0.0, 0.0, 0.0)
DOWN = (-1.57, 0.0, 0.0)      # wheel and caster links: z of the link along +y of base_link
OPTICAL = (-1.57, 0.0, -1.57)  # optical frame: z forward, x right, y down

# --- doc/turtlebot3.md 1.3 (and 4.5): joint -> (type, parent, child, xyz, rpy) --------------------

BURGER_JOINTS = {
    "base_joint": ("fixed", "base_footprint", "base_link", (0, 0, 0.010), ZERO),
    "wheel_left_joint": ("continuous", "base_link", "wheel_left_link", (0, 0.08, 0.023), DOWN),
    "wheel_right_joint": ("continuous", "base_link", "wheel_right_link", (0, -0.080, 0.023), DOWN),
    "imu_joint": ("fixed", "base_link", "imu_link", (-0.032, 0, 0.068), ZERO),
    "scan_joint": ("fixed", "base_link", "base_scan", (-0.032, 0, 0.172), ZERO),
    "caster_back_joint": ("fixed", "base_link", "caster_back_link", (-0.081, 0, -0.004), DOWN),
}
WAFFLE_BASE_JOINTS = {
    "base_joint": ("fixed", "base_footprint", "base_link", (0, 0, 0.010), ZERO),
    "wheel_left_joint": ("continuous", "base_link", "wheel_left_link", (0, 0.144, 0.023), DOWN),
    "wheel_right_joint": ("continuous", "base_link", "wheel_right_link", (0, -0.144, 0.023), DOWN),
    "imu_joint": ("fixed", "base_link", "imu_link", (0, 0, 0.068), ZERO),
    "scan_joint": ("fixed", "base_link", "base_scan", (-0.064, 0, 0.122), ZERO),
    "caster_back_right_joint": ("fixed", "base_link", "caster_back_right_link",
                                (-0.177, -0.064, -0.004), DOWN),
    "caster_back_left_joint": ("fixed", "base_link", "caster_back_left_link",
                               (-0.177, 0.064, -0.004), DOWN),
}
WAFFLE_JOINTS = dict(WAFFLE_BASE_JOINTS, **{
    "camera_joint": ("fixed", "base_link", "camera_link", (0.064, -0.065, 0.094), ZERO),
    "camera_rgb_joint": ("fixed", "camera_link", "camera_rgb_frame", (0.005, 0.018, 0.013), ZERO),
    "camera_rgb_optical_joint": ("fixed", "camera_rgb_frame", "camera_rgb_optical_frame", ZERO,
                                 OPTICAL),
    "camera_depth_joint": ("fixed", "camera_link", "camera_depth_frame", (0.005, 0.028, 0.013),
                           ZERO),
    "camera_depth_optical_joint": ("fixed", "camera_depth_frame", "camera_depth_optical_frame",
                                   ZERO, OPTICAL),
})
WAFFLE_PI_JOINTS = dict(WAFFLE_BASE_JOINTS, **{
    "camera_joint": ("fixed", "base_link", "camera_link", (0.073, -0.011, 0.084), ZERO),
    "camera_rgb_joint": ("fixed", "camera_link", "camera_rgb_frame", (0.003, 0.011, 0.009), ZERO),
    "camera_rgb_optical_joint": ("fixed", "camera_rgb_frame", "camera_rgb_optical_frame", ZERO,
                                 OPTICAL),
})
AUTORACE_JOINTS = dict(BURGER_JOINTS, **{
    "camera_joint": ("fixed", "base_link", "camera_link", (0.040, -0.011, 0.130), (0, 0.174, 0)),
    "camera_rgb_joint": ("fixed", "camera_link", "camera_rgb_frame", (0.003, 0.011, 0.009), ZERO),
    "camera_rgb_optical_joint": ("fixed", "camera_rgb_frame", "camera_rgb_optical_frame", ZERO,
                                 OPTICAL),
})

# --- doc/turtlebot3.md 1.2: link -> (mass, (ixx, ixy, ixz, iyy, iyz, izz)), None = no inertial ----

WHEEL = (0.02849894, (1.1175580e-5, -4.2369783e-11, -5.9381719e-9, 1.1192413e-5, -1.4400107e-11,
                      2.0712558e-5))
SMALL = (0.001, 0, 0, 0.001, 0, 0.001)
BURGER_LINKS = {
    "base_footprint": None,
    "base_link": (0.82573504, (2.2124416e-3, -1.2294101e-5, 3.4938785e-5, 2.1193702e-3,
                               -5.0120904e-6, 2.0064271e-3)),
    "wheel_left_link": WHEEL, "wheel_right_link": WHEEL,
    "caster_back_link": (0.005, SMALL),
    "imu_link": None,
    "base_scan": (0.114, SMALL),
}
WAFFLE_BASE_LINKS = {
    "base_footprint": None,
    "base_link": (1.3729096, (8.7002718e-3, -4.7576583e-5, 1.1160499e-4, 8.6195418e-3,
                              -3.5422299e-6, 1.4612727e-2)),
    "wheel_left_link": WHEEL, "wheel_right_link": WHEEL,
    "caster_back_left_link": (0.005, SMALL), "caster_back_right_link": (0.005, SMALL),
    "imu_link": None,
    "base_scan": (0.114, SMALL),
}
CAMERA_RGB_LINKS = {"camera_link": None, "camera_rgb_frame": None, "camera_rgb_optical_frame": None}
WAFFLE_LINKS = dict(WAFFLE_BASE_LINKS, camera_depth_frame=None, camera_depth_optical_frame=None,
                    **CAMERA_RGB_LINKS)
WAFFLE_PI_LINKS = dict(WAFFLE_BASE_LINKS, **CAMERA_RGB_LINKS)
AUTORACE_LINKS = dict(BURGER_LINKS, **CAMERA_RGB_LINKS)

# --- doc/turtlebot3.md 1.1: link -> (shape, size, xyz in link) of its one collision ---------------

WHEEL_SHAPE = ("cylinder", (0.033, 0.018), ZERO)
CASTER_SHAPE = ("box", (0.030, 0.009, 0.020), (0, 0.001, 0))
LDS_SHAPE = ("cylinder", (0.055, 0.0315), (0.015, 0, -0.0065))
PI_CAMERA_SHAPE = ("box", (0.015, 0.030, 0.027), (0.005, 0.011, 0.013))
BURGER_SHAPES = {
    "base_link": ("box", (0.140, 0.140, 0.143), (-0.032, 0, 0.070)),
    "wheel_left_link": WHEEL_SHAPE, "wheel_right_link": WHEEL_SHAPE,
    "caster_back_link": CASTER_SHAPE, "base_scan": LDS_SHAPE,
}
WAFFLE_BASE_SHAPES = {
    "base_link": ("box", (0.266, 0.266, 0.094), (-0.064, 0, 0.047)),
    "wheel_left_link": WHEEL_SHAPE, "wheel_right_link": WHEEL_SHAPE,
    "caster_back_left_link": CASTER_SHAPE, "caster_back_right_link": CASTER_SHAPE,
    "base_scan": LDS_SHAPE,
}
WAFFLE_SHAPES = dict(WAFFLE_BASE_SHAPES,
                     camera_link=("box", (0.012, 0.132, 0.020), (0.003, 0.065, 0.007)))
WAFFLE_PI_SHAPES = dict(WAFFLE_BASE_SHAPES, camera_link=PI_CAMERA_SHAPE)
AUTORACE_SHAPES = dict(BURGER_SHAPES, camera_link=PI_CAMERA_SHAPE)

# doc/turtlebot3.md 1.4: RViz colours of the base (light_black) and of the wheels and LDS (dark)
COLOURS = {"base_link": (0.4, 0.4, 0.4, 1.0), "wheel_left_link": (0.3, 0.3, 0.3, 1.0),
           "wheel_right_link": (0.3, 0.3, 0.3, 1.0), "base_scan": (0.3, 0.3, 0.3, 1.0)}

# (model, with_camera) -> robot name, file name, links, joints, collision shapes
ROBOTS = {
    ("burger", False): ("turtlebot3_burger", "turtlebot3_burger.urdf",
                        BURGER_LINKS, BURGER_JOINTS, BURGER_SHAPES),
    ("burger", True): ("turtlebot3_burger_for_autorace", "turtlebot3_burger_for_autorace.urdf",
                       AUTORACE_LINKS, AUTORACE_JOINTS, AUTORACE_SHAPES),
    ("waffle", False): ("turtlebot3_waffle", "turtlebot3_waffle.urdf",
                        WAFFLE_LINKS, WAFFLE_JOINTS, WAFFLE_SHAPES),
    ("waffle_pi", False): ("turtlebot3_waffle_pi", "turtlebot3_waffle_pi.urdf",
                           WAFFLE_PI_LINKS, WAFFLE_PI_JOINTS, WAFFLE_PI_SHAPES),
}
ALL = pytest.mark.parametrize("key", list(ROBOTS), ids=lambda k: k[0] + ("_camera" if k[1] else ""))


def load(key):
    return read_urdf(urdf_path(*key))


@ALL
def test_file_and_robot_name(key):
    name, filename = ROBOTS[key][:2]
    path = urdf_path(*key)
    assert os.path.basename(path) == filename and os.path.isfile(path)
    assert os.path.basename(os.path.dirname(path)) == "urdf"
    assert load(key).name == name


@ALL
def test_joints_match_facts(key):
    joints = ROBOTS[key][3]
    robot = load(key)
    assert set(robot.joints) == set(joints)
    for name, (kind, parent, child, xyz, rpy) in joints.items():
        joint = robot.joints[name]
        assert (joint.type, joint.parent, joint.child) == (kind, parent, child), name
        assert joint.origin.xyz == pytest.approx(xyz, abs=1e-12), name
        assert joint.origin.rpy == pytest.approx(rpy, abs=1e-12), name
        if kind == "continuous":
            assert joint.axis == (0.0, 0.0, 1.0), name


@ALL
def test_links_masses_and_inertias_match_facts(key):
    links = ROBOTS[key][2]
    robot = load(key)
    assert set(robot.links) == set(links)
    assert robot.root_link == "base_footprint"
    for name, expected in links.items():
        inertial = robot.links[name].inertial
        if expected is None:
            assert inertial is None, name
            continue
        mass, inertia = expected
        assert inertial.mass == pytest.approx(mass, rel=1e-9), name
        assert inertial.inertia == pytest.approx(inertia, rel=1e-9, abs=1e-15), name
        assert (inertial.origin.xyz, inertial.origin.rpy) == (ZERO, ZERO), name


@ALL
def test_collision_and_visual_shapes_match_facts(key):
    shapes = ROBOTS[key][4]
    robot = load(key)
    for name, link in robot.links.items():
        if name not in shapes:
            assert link.collisions == () and link.visuals == (), name
            continue
        shape, size, xyz = shapes[name]
        assert len(link.collisions) == 1 and len(link.visuals) == 1, name
        for part in (link.collisions[0], link.visuals[0]):
            assert part.geometry.shape == shape, name
            assert part.geometry.size == pytest.approx(size, abs=1e-12), name
            assert part.origin.xyz == pytest.approx(xyz, abs=1e-12), name
            assert part.origin.rpy == ZERO, name
        assert link.visuals[0].rgba is not None, name
    for name, rgba in COLOURS.items():
        assert robot.links[name].visuals[0].rgba == pytest.approx(rgba), name


@ALL
def test_derived_heights_and_mass(key):
    robot = load(key)
    footprint = robot.root_link
    burger = key[0] == "burger"
    scan_z = robot.transform(footprint, "base_scan")[2, 3]
    assert scan_z == pytest.approx(0.182 if burger else 0.132, abs=1e-9)
    for side, sign in (("left", 1), ("right", -1)):
        wheel = robot.transform(footprint, "wheel_%s_link" % side)
        assert wheel[2, 3] == pytest.approx(0.033, abs=1e-9)
        assert wheel[1, 3] == pytest.approx(sign * (0.080 if burger else 0.144), abs=1e-9)
        # spin axis along +y of base_link: positive joint speed rolls the robot forward
        axis = wheel[:3, :3] @ robot.joints["wheel_%s_joint" % side].axis
        assert axis == pytest.approx((0, 1, 0), abs=1e-3)
    assert robot.mass == pytest.approx(1.00 if burger else 1.55, abs=0.005)


@ALL
def test_robot_rests_on_its_wheels(key):
    """Every collision box of the body stays above the floor (caster bottom ~0.5 mm up);
    the wheel cylinders touch z = 0 in base_footprint."""
    robot = load(key)
    lowest = {}
    for name, link in robot.links.items():
        for collision in link.collisions:
            pose = robot.transform("base_footprint", name) @ collision.origin.matrix()
            if collision.geometry.shape == "box":
                half = np.array(collision.geometry.size) / 2
                corners = np.array([[sx, sy, sz, 1] for sx in (-1, 1) for sy in (-1, 1)
                                    for sz in (-1, 1)]) * np.append(half, 1)
                lowest[name] = min((pose @ corners.T)[2])
            elif collision.geometry.shape == "cylinder":
                radius, length = collision.geometry.size
                axis_z = pose[2, 2]
                lowest[name] = pose[2, 3] - abs(axis_z) * length / 2 - np.hypot(
                    pose[2, 0], pose[2, 1]) * radius
    for wheel in ("wheel_left_link", "wheel_right_link"):
        assert lowest.pop(wheel) == pytest.approx(0.0, abs=1e-4)
    assert min(lowest.values()) > 0.0
    casters = [v for k, v in lowest.items() if k.startswith("caster")]
    assert casters and all(v == pytest.approx(0.0005, abs=1e-4) for v in casters)


@pytest.mark.parametrize("key", [k for k in ROBOTS if k != ("burger", False)],
                         ids=lambda k: k[0] + ("_camera" if k[1] else ""))
def test_optical_frame_looks_forward(key):
    """z forward, x right, y down in base_link (doc/turtlebot3.md 1.3); AutoRace 10 deg down."""
    robot = load(key)
    rotation = robot.transform("base_link", "camera_rgb_optical_frame")[:3, :3]
    pitch = 0.174 if key[1] else 0.0
    forward = (np.cos(pitch), 0, -np.sin(pitch))
    assert rotation[:, 2] == pytest.approx(forward, abs=2e-3)
    assert rotation[:, 0] == pytest.approx((0, -1, 0), abs=2e-3)
    assert rotation[:, 1] == pytest.approx((-np.sin(pitch), 0, -np.cos(pitch)), abs=2e-3)


def test_waffle_pi_camera_rgb_frame_position():
    robot = load(("waffle_pi", False))
    assert robot.transform("base_footprint", "camera_rgb_frame")[:3, 3] == pytest.approx(
        (0.076, 0.0, 0.103), abs=1e-9)


def test_transform_composes_and_inverts():
    robot = load(("waffle", False))
    there = robot.transform("camera_depth_optical_frame", "wheel_left_link")
    back = robot.transform("wheel_left_link", "camera_depth_optical_frame")
    assert there @ back == pytest.approx(np.eye(4), abs=1e-12)
    assert robot.transform("base_scan", "base_scan") == pytest.approx(np.eye(4))
    assert robot.parent_joint("camera_link").name == "camera_joint"
    assert robot.parent_joint("base_footprint") is None
    with pytest.raises(KeyError, match="no_such_link"):
        robot.transform("base_link", "no_such_link")


def test_urdf_path_choices():
    assert urdf_path("waffle", with_camera=True) == urdf_path("waffle")
    assert urdf_path("burger", with_camera=True) != urdf_path("burger")
    with pytest.raises(ModelError, match="burger, waffle, waffle_pi"):
        urdf_path("waffle_pie")


@ALL
def test_pybullet_loads_the_file(key):
    robot = load(key)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(urdf_path(*key), physicsClientId=client)
        assert pybullet.getBodyInfo(body, physicsClientId=client) == (
            b"base_footprint", ROBOTS[key][0].encode())
        found = {}
        for index in range(pybullet.getNumJoints(body, physicsClientId=client)):
            info = pybullet.getJointInfo(body, index, physicsClientId=client)
            found[info[1].decode()] = (info[2], info[12].decode(), info[14])
    finally:
        pybullet.disconnect(client)
    assert set(found) == set(robot.joints)
    for name, (kind, child, parent_frame_xyz) in found.items():
        expected = pybullet.JOINT_REVOLUTE if name.startswith("wheel_") else pybullet.JOINT_FIXED
        assert kind == expected, name
        assert child == robot.joints[name].child, name
        assert parent_frame_xyz == pytest.approx(robot.joints[name].origin.xyz, abs=1e-9), name


# --- malformed files: (text, words the one-line message must hold, besides the file name) -------

ROBOT = '<robot name="r">\n  <link name="a"/>\n  <link name="b"/>\n%s\n</robot>\n'
JOINT_AB = '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
BAD = {
    "malformed_xml": ('<robot name="r">\n  <link name="a">\n</robot>\n',
                      [":3:", "malformed XML", "mismatched tag"]),
    "empty": ("", [":1:", "malformed XML", "no element found"]),
    "not_robot": ('<sdf version="1.6"/>\n', [":1:", "<sdf>", "<robot>"]),
    "robot_without_name": ('<robot>\n  <link name="a"/>\n</robot>\n',
                           [":1:", "<robot>", "missing attribute 'name'"]),
    "link_without_name": ('<robot name="r">\n  <link/>\n</robot>\n',
                          [":2:", "<link>", "missing attribute 'name'"]),
    "duplicate_link": ('<robot name="r">\n  <link name="a"/>\n  <link name="a"/>\n</robot>\n',
                       [":3:", "link 'a': defined twice"]),
    "joint_without_child": (ROBOT % '<joint name="j" type="fixed"><parent link="a"/></joint>',
                            [":4:", "joint 'j': missing <child>"]),
    "joint_unknown_link": (ROBOT % JOINT_AB.replace('"b"', '"c"'),
                           [":4:", "joint 'j' <child>", "'c' is not defined"]),
    "joint_bad_type": (ROBOT % JOINT_AB.replace("fixed", "hinge"),
                       [":4:", "joint 'j': type 'hinge'", "continuous"]),
    "revolute_without_limit": (ROBOT % JOINT_AB.replace("fixed", "revolute"),
                               [":4:", "joint 'j': missing <limit>"]),
    "origin_not_numbers": (ROBOT % JOINT_AB.replace("</joint>", '\n<origin xyz="0 a 0"/></joint>'),
                           [":5:", "joint 'j' <origin>", "xyz='0 a 0'"]),
    "origin_two_numbers": (ROBOT % JOINT_AB.replace(
        "</joint>", '<origin rpy="0 0"/></joint>'), [":4:", "<origin>", "rpy='0 0'", "3 numbers"]),
    "axis_nan": (ROBOT % JOINT_AB.replace("</joint>", '<axis xyz="0 0 nan"/></joint>'),
                 [":4:", "<axis>", "xyz='0 0 nan'"]),
    "two_parents": (ROBOT % (JOINT_AB + '\n<joint name="k" type="fixed"><parent link="a"/>'
                             '<child link="b"/></joint>'),
                    [":5:", "joint 'k': link 'b' already has a parent", "'j' (line 4)"]),
    "two_roots": (ROBOT % "", [":1:", "robot 'r': 2 root links", "a, b"]),
    "loop": (ROBOT % (JOINT_AB + '\n<joint name="k" type="fixed"><parent link="b"/>'
                      '<child link="a"/></joint>'), [":1:", "no root link"]),
    "loop_cut_off": ('<robot name="r">\n  <link name="root"/>\n  <link name="a"/>\n'
                     '  <link name="b"/>\n' + JOINT_AB + '\n<joint name="k" type="fixed">'
                     '<parent link="b"/><child link="a"/></joint>\n</robot>\n',
                     [":1:", "a, b", "cut off", "'root'"]),
    "mass_not_number": ('<robot name="r">\n  <link name="a">\n    <inertial>\n'
                        '      <mass value="heavy"/>\n    </inertial>\n  </link>\n</robot>\n',
                        [":4:", "link 'a' <mass>", "value='heavy' is not a number"]),
    "inertia_missing_izz": ('<robot name="r">\n  <link name="a"><inertial><mass value="1"/>\n'
                            '  <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"/>\n'
                            '  </inertial></link>\n</robot>\n',
                            [":3:", "link 'a' <inertia>", "missing attribute 'izz'"]),
    "inertial_without_mass": ('<robot name="r">\n  <link name="a"><inertial/></link>\n</robot>\n',
                              [":2:", "link 'a' <inertial>", "missing <mass>"]),
    "geometry_empty": ('<robot name="r">\n  <link name="a">\n    <collision><geometry/>'
                       '</collision>\n  </link>\n</robot>\n',
                       [":3:", "link 'a' <geometry>", "exactly one"]),
    "box_negative": ('<robot name="r">\n  <link name="a">\n    <collision><geometry>\n'
                     '      <box size="0.1 -0.1 0.1"/></geometry></collision>\n'
                     '  </link>\n</robot>\n',
                     [":4:", "link 'a' <box>", "positive"]),
    "cylinder_without_radius": ('<robot name="r">\n  <link name="a"><visual><geometry>\n'
                                '    <cylinder length="1"/></geometry></visual></link>\n</robot>\n',
                                [":3:", "link 'a' <cylinder>", "missing attribute 'radius'"]),
    "undefined_material": ('<robot name="r">\n  <link name="a"><visual><geometry><sphere '
                           'radius="1"/></geometry>\n    <material name="chrome"/>'
                           '</visual></link>\n</robot>\n',
                           [":3:", "link 'a' material 'chrome'", "no <color>"]),
    "colour_out_of_range": ('<robot name="r">\n  <material name="x">\n    <color rgba="0 0 255 1"/>'
                            '\n  </material>\n  <link name="a"/>\n</robot>\n',
                            [":3:", "material 'x' <color>", "0 to 1"]),
}


@pytest.mark.parametrize("case", list(BAD))
def test_malformed_file_names_file_line_and_fault(tmp_path, case):
    text, words = BAD[case]
    path = tmp_path / ("%s.urdf" % case)
    path.write_text(text)
    with pytest.raises(UrdfError) as err:
        read_urdf(path)
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith(str(path) + ":")
    for word in words:
        assert word in message, (word, message)


def test_missing_file_names_it(tmp_path):
    path = tmp_path / "nowhere" / "turtlebot3_tank.urdf"
    with pytest.raises(UrdfError,
                       match="turtlebot3_tank.urdf: cannot read URDF file: No such file"):
        read_urdf(path)
