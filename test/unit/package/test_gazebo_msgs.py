"""The repository's gazebo_msgs (msgs/gazebo_msgs) is wire-identical to gazebo_ros_pkgs'
gazebo_msgs 2.9.2 (noetic-devel): every message and service has upstream's md5sum. No ROS master.

The md5sums are computed with genmsg straight from the repository's .msg/.srv files and the
installed std_msgs/geometry_msgs/trajectory_msgs definitions, so this needs no build and fails as
soon as a field's type, name or order (or a constant) changes. Where the workspace has been
built, the generated Python classes must carry the same md5sums.

Sources of the expected values: doc/turtlebot3.md 7.1 for the types listed there; the others are the
md5sums found in public generated code for upstream's gazebo_msgs (roslisp, rosnodejs, ROS.NET,
rosserial), which agree with each other.
"""
import importlib
import os
import re

import pytest

import unit_paths

genmsg = pytest.importorskip("genmsg", reason="python3-genmsg is not installed")
from genmsg import msg_loader  # noqa: E402
from genmsg.gentools import compute_md5  # noqa: E402

PKG_DIR = os.path.join(unit_paths.ROOT, "msgs", "gazebo_msgs")
DEPENDENCIES = ("std_msgs", "geometry_msgs", "trajectory_msgs")

# Messages: md5sum (doc/turtlebot3.md 7.1 unless marked "public").
MESSAGES = {
    "ModelState": "9330fd35f2fcd82d457e54bd54e10593",
    "ModelStates": "48c080191eb15c41858319b4d8a609c2",
    "LinkState": "0818ebbf28ce3a08d48ab1eaa7309ebe",
    "LinkStates": "48c080191eb15c41858319b4d8a609c2",
    "ODEPhysics": "667d56ddbd547918c32d1934503dc335",
    "PerformanceMetrics": "884f71fd5037b886ec5e126b83c4425a",
    "SensorPerformanceMetric": "01762ded18cfe9ebc7c8222667c99547",   # public
    "ContactState": "48c0ffb054b8c444f870cecea1ee50d9",              # public
    "ContactsState": "acbcb1601a8e525bf72509f18e6f668d",             # public
    "ODEJointProperties": "1b744c32a920af979f53afe2f9c3511f",        # public
    "WorldState": "de1a9de3ab7ba97ac0e9ec01a4eb481e",                # public
}

# Services: (service md5, request md5, response md5); None where no source gives the value.
# rospy and roscpp compare the service md5.
SERVICES = {
    "GetModelState": ("4c515e936d3319c9610c559c60bfc3d4", "19d412713cefe4a67437e17a951e759e",
                      "ccd51739bb00f0141629e87b792e92b9"),
    "SetModelState": ("5b3ab0281d4f5445def017e3a2e4a07b", "cb042b0e91880f4661b29ea5b6234350",
                      "2ec6f3eff0161f4257b808b12bc830c2"),
    "GetLinkState": ("09d6c98cce97b35f7ab9bd70300657ab", "7551675c30aaa71f7c288d4864552001",
                     "8ba55ad34f9c072e75c0de57b089753b"),
    "SetLinkState": ("8a5146eb66ae4d26b0860b08f3f271be", "22a2c757d56911b6f27868159e9a872d",
                     "2ec6f3eff0161f4257b808b12bc830c2"),
    "SpawnModel": ("9ed9c82c96abe1a00c3e8cdaeee24413", "6d0eba5753761cd57e6263a056b79930",
                   "2ec6f3eff0161f4257b808b12bc830c2"),
    "DeleteModel": ("9ce56b4e9e54616de25d796dc972a262", "ea31c8eab6fc401383cf528a7c0984ba",
                    "2ec6f3eff0161f4257b808b12bc830c2"),
    "GetWorldProperties": ("36bb0f2eccf4d8be971410c22818ba3f", "d41d8cd98f00b204e9800998ecf8427e",
                           "36bb0f2eccf4d8be971410c22818ba3f"),
    "GetModelProperties": ("5717f7bd34ed990fa80e28b3015027a3", "ea31c8eab6fc401383cf528a7c0984ba",
                           "b7f370938ef77b464b95f1bab3ec5028"),
    "GetPhysicsProperties": ("575a5e74786981b7df2e3afc567693a6",
                             "d41d8cd98f00b204e9800998ecf8427e",
                             "575a5e74786981b7df2e3afc567693a6"),
    "SetPhysicsProperties": ("97e2057080558ce4730434b5fae75c91",
                             "abd9f82732b52b92e9d6bb36e6a82452",
                             "2ec6f3eff0161f4257b808b12bc830c2"),
    "SetModelConfiguration": ("10e3139d3b669c40afc057d38956fff7", None, None),
    "ApplyBodyWrench": ("585b9f9618aa0581b207e2f2d90866bc", None, None),
    "ApplyJointEffort": ("c0039811b8cc919490b3cff748cdf46b", None, None),
    # public generated code from here on
    "BodyRequest": ("5eade9afe7f232d78005bd0cafeab755", "5eade9afe7f232d78005bd0cafeab755",
                    "d41d8cd98f00b204e9800998ecf8427e"),
    "JointRequest": ("0be1351618e1dc030eb7959d9a4902de", "0be1351618e1dc030eb7959d9a4902de",
                     "d41d8cd98f00b204e9800998ecf8427e"),
    "DeleteLight": ("ae11ea8100d536d5b92c2b5917abf912", None, None),
    "GetJointProperties": ("7b30be900f50aa21efec4a0ec92d91c9",
                           "0be1351618e1dc030eb7959d9a4902de", None),
    "SetJointProperties": ("15a76e921b1410c698d82782ea5fa370", None, None),
    "GetLightProperties": ("df2cef87e13e2e6990e81e8aaa454c19", None, None),
    "SetLightProperties": ("e6f13430c57278bb364aca53a1bf5ebf",
                           "10d953f2306aec18460eb80dd94fdd47", None),
    "GetLinkProperties": ("0e06a70386d0ee3fb880c02f23fcd821",
                          "7d82d60381f1b66a30f2157f60884345", None),
    "SetLinkProperties": ("d534ce1b36ee99de0ffa806c3a6348f0", None, None),
    "SetJointTrajectory": ("88f5c10979e3f9649d5ae87a3b12aa65", None, None),
}


def _definition_dirs():
    """Where the installed std_msgs/geometry_msgs/trajectory_msgs .msg files are."""
    try:
        import rospkg
        rospack = rospkg.RosPack()
    except ImportError:
        rospack = None
    paths = {"gazebo_msgs": [os.path.join(PKG_DIR, "msg")]}
    for pkg in DEPENDENCIES:
        candidates = []
        if rospack is not None:
            try:
                candidates.append(rospack.get_path(pkg))
            except rospkg.ResourceNotFound:
                pass
        candidates += [os.path.join(r, pkg) for r in ("/opt/ros/noetic/share", "/usr/share")]
        found = [os.path.join(c, "msg") for c in candidates
                 if os.path.isdir(os.path.join(c, "msg"))]
        if not found:
            pytest.skip("the %s message definitions are not installed" % pkg)
        paths[pkg] = found[:1]
    return paths


@pytest.fixture(scope="module")
def loader():
    search_path = _definition_dirs()
    context = msg_loader.MsgContext.create_default()

    def load(kind, name):
        full_name = "gazebo_msgs/" + name
        path = os.path.join(PKG_DIR, kind, name + "." + kind)
        if kind == "msg":
            spec = msg_loader.load_msg_from_file(context, path, full_name)
        else:
            spec = msg_loader.load_srv_from_file(context, path, full_name)
        msg_loader.load_depends(context, spec, search_path)
        return context, spec

    return load


def _names(kind):
    return sorted(f[:-4] for f in os.listdir(os.path.join(PKG_DIR, kind)) if f.endswith("." + kind))


def test_package_has_exactly_upstreams_types():
    assert _names("msg") == sorted(MESSAGES)
    assert _names("srv") == sorted(SERVICES)


def test_cmakelists_generates_every_definition():
    with open(os.path.join(PKG_DIR, "CMakeLists.txt")) as f:
        cmake = f.read()
    listed_msgs = re.findall(r"^\s*(\w+)\.msg\s*$", cmake, re.M)
    listed_srvs = re.findall(r"^\s*(\w+)\.srv\s*$", cmake, re.M)
    assert sorted(listed_msgs) == _names("msg")
    assert sorted(listed_srvs) == _names("srv")


def test_package_xml_is_bsd_and_named_gazebo_msgs():
    with open(os.path.join(PKG_DIR, "package.xml")) as f:
        manifest = f.read()
    assert '<package format="2">' in manifest
    assert "<name>gazebo_msgs</name>" in manifest
    assert "<license>BSD</license>" in manifest
    for dep in DEPENDENCIES:
        assert "<depend>%s</depend>" % dep in manifest
    assert os.path.isfile(os.path.join(PKG_DIR, "LICENSE"))


@pytest.mark.parametrize("name", sorted(MESSAGES))
def test_message_md5(loader, name):
    context, spec = loader("msg", name)
    assert compute_md5(context, spec) == MESSAGES[name]


@pytest.mark.parametrize("name", sorted(SERVICES))
def test_service_md5(loader, name):
    context, spec = loader("srv", name)
    service, request, response = SERVICES[name]
    assert compute_md5(context, spec) == service
    if request is not None:
        assert compute_md5(context, spec.request) == request
    if response is not None:
        assert compute_md5(context, spec.response) == response


def test_no_constants_except_joint_types(loader):
    """Upstream declares constants only in GetJointProperties' response (the joint types)."""
    for name in MESSAGES:
        assert loader("msg", name)[1].constants == [], name
    for name in SERVICES:
        spec = loader("srv", name)[1]
        assert spec.request.constants == [], name
        expected = ([("REVOLUTE", 0), ("CONTINUOUS", 1), ("PRISMATIC", 2), ("FIXED", 3),
                     ("BALL", 4), ("UNIVERSAL", 5)] if name == "GetJointProperties" else [])
        assert [(c.name, c.val) for c in spec.response.constants] == expected, name


def _generated(kind):
    try:
        return importlib.import_module("gazebo_msgs." + kind)
    except ImportError:
        pytest.skip("gazebo_msgs is not built (run tools/setup.sh, then source "
                    "catkin_ws/devel/setup.bash)")


@pytest.mark.parametrize("name", sorted(MESSAGES))
def test_generated_message_class_md5(name):
    cls = getattr(_generated("msg"), name)
    assert cls._type == "gazebo_msgs/" + name
    assert cls._md5sum == MESSAGES[name]


@pytest.mark.parametrize("name", sorted(SERVICES))
def test_generated_service_class_md5(name):
    module = _generated("srv")
    service, request, response = SERVICES[name]
    assert getattr(module, name)._md5sum == service      # what rospy checks on the wire
    assert getattr(module, name)._type == "gazebo_msgs/" + name
    if request is not None:
        assert getattr(module, name + "Request")._md5sum == request
    if response is not None:
        assert getattr(module, name + "Response")._md5sum == response
