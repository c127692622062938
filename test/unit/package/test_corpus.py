"""make corpus's own logic, without the corpus or a ROS master: the manifest
(tools/corpus/manifest.json) and its checks, the model resolver of tools/corpus/fetch_corpus.py,
the free-pose finder (bench/corpus_pose.py) in a small world of our own, and the measures and
table of bench/corpus_metrics.py."""
import copy
import json
import math
import os
import sys

import numpy as np
import pytest

import unit_paths

sys.path.insert(0, os.path.join(unit_paths.ROOT, "bench"))
sys.path.insert(0, os.path.join(unit_paths.ROOT, "tools", "corpus"))
import corpus_metrics  # noqa: E402
import corpus_pose  # noqa: E402
import fetch_corpus  # noqa: E402

# Kept out of the corpus for acceptance: (repository, path part) pairs.
KEPT_OUT = [("aws-robotics/aws-robomaker-hospital-world", ""),
            ("aws-robotics/aws-robomaker-racetrack-world", ""),
            ("aws-robotics/aws-robomaker-small-house-world", ""),
            ("aws-robotics/aws-robomaker-bookstore-world", ""),
            ("gazebosim/gazebo-classic", "worlds/cafe.world"),
            ("", "gazebo_models_worlds_collection"),
            ("clearpathrobotics/cpr_gazebo", ""),
            ("husarion/gazebo_worlds", ""),
            ("larics/larics_gazebo_worlds", ""),
            ("PX4/PX4-SITL_gazebo-classic", "")]


@pytest.fixture
def manifest():
    return fetch_corpus.load_manifest()


def test_manifest_names_at_least_50_worlds_with_their_sources(manifest):
    worlds = manifest["worlds"]
    assert len(worlds) >= 50
    for world in worlds:
        assert fetch_corpus.HEX40.match(world["commit"]), world["name"]
        assert world["path"].endswith((".world", ".sdf", ".model")), world["name"]
        env = fetch_corpus.world_env("/corpus", world)
        assert env["GAZEBO_MODEL_PATH"] == os.path.join("/corpus", world["name"], "models")
        for source in list(world["models"].values()) + list(world.get("extra", {}).values()):
            assert fetch_corpus.HEX40.match(manifest["repos"][source["repo"]])
    assert len({w["repo"] for w in worlds}) >= 20


def test_manifest_leaves_out_the_worlds_kept_for_acceptance(manifest):
    for world in manifest["worlds"]:
        sources = [(world["repo"], world["path"])] + [
            (s["repo"], s["path"]) for s in world["models"].values()]
        for repo, path in sources:
            for kept_repo, kept_part in KEPT_OUT:
                if kept_repo:
                    assert not (repo == kept_repo and kept_part in path), (world["name"], path)
                else:
                    assert kept_part not in repo + "/" + path, (world["name"], repo)


@pytest.mark.parametrize("spoil, says", [
    (lambda m: m["worlds"][0].update(commit="abc"), "40-hex commit"),
    (lambda m: m["worlds"][1].update(name=m["worlds"][0]["name"]), "not a new"),
    (lambda m: m["worlds"][0].update(sha256=""), "sha256"),
    (lambda m: m["repos"].update({"osrf/gazebo_models": "HEAD"}), "40-hex"),
    (lambda m: next(iter(m["worlds"][0]["models"].values())).update(repo="x/y"), "known repo"),
])
def test_a_spoilt_manifest_is_refused_in_one_line(manifest, spoil, says):
    spoilt = copy.deepcopy(manifest)
    spoil(spoilt)
    with pytest.raises(fetch_corpus.ManifestError, match=says):
        fetch_corpus.check_manifest(spoilt)


def test_build_says_what_is_missing_when_there_are_no_snapshots(manifest, tmp_path):
    lines = []

    class Out:
        def write(self, text):
            lines.extend(t for t in text.splitlines() if t)
    small = dict(manifest, worlds=manifest["worlds"][:2])
    missing = fetch_corpus.build(small, str(tmp_path / "corpus"), str(tmp_path / "no_mirrors"),
                                 out=Out())
    assert missing == len(lines) > 0
    assert all(line.split(":")[0] in {w["name"] for w in small["worlds"]} for line in lines)
    assert any("read_file" in line or "fetch github:" in line for line in lines)


def test_resolver_follows_includes_into_model_folders():
    trees = {
        "me/world_repo": ["pkg/worlds/w.world", "pkg/models/room/model.config",
                          "other/models/room/model.config", "pkg/models/course/a/model.config"],
        "osrf/gazebo_models": ["table/model.config", "room/model.config", "lamp/model.config"],
    }
    texts = {("me/world_repo", "pkg/models/room"): "<uri>model://table</uri>",
             ("osrf/gazebo_models", "table"): "<uri>model://lamp/meshes/l.dae</uri>"}
    world = ("<include><uri>model://room</uri></include><uri>model://course/a</uri>"
             "<uri>model://missing</uri>")
    found, unresolved = fetch_corpus.resolve(
        world, "pkg/worlds/w.world", list(trees.items()),
        lambda repo, folder: texts.get((repo, folder), ""))
    assert found == {"room": ("me/world_repo", "pkg/models/room"),
                     "course": ("me/world_repo", "pkg/models/course"),
                     "table": ("osrf/gazebo_models", "table"),
                     "lamp": ("osrf/gazebo_models", "lamp")}
    assert unresolved == ["missing"]


WORLD = """<?xml version="1.0"?>
<sdf version="1.6"><world name="room">{ground}{walls}
  <model name="block"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="l">
    <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link>
  </model>
</world></sdf>
"""
GROUND = """<model name="ground"><static>true</static><link name="l"><collision name="c">
  <geometry><plane><normal>0 0 1</normal><size>40 40</size></plane></geometry></collision>
  </link></model>"""
WALL = """<model name="wall_{n}"><static>true</static><pose>{x} {y} 0.5 0 0 {yaw}</pose>
  <link name="l"><collision name="c"><geometry><box><size>4.2 0.1 1</size></box></geometry>
  </collision></link></model>"""


def test_free_pose_finder_finds_a_clear_spot_inside_a_room(tmp_path):
    """A 4 x 4 m walled room with a 1 m block in its middle: the pose found is inside the room,
    at least CLEARANCE from the walls and from the block, on the floor."""
    walls = "".join(WALL.format(n=n, x=x, y=y, yaw=yaw) for n, (x, y, yaw) in enumerate(
        [(2, 0, math.pi / 2), (-2, 0, math.pi / 2), (0, 2, 0), (0, -2, 0)]))
    path = tmp_path / "room.world"
    path.write_text(WORLD.format(ground=GROUND, walls=walls))
    pose = corpus_pose.find_free_pose(str(path))
    assert "error" not in pose, pose
    x, y = pose["x"], pose["y"]
    inner = 2.0 - 0.05 - corpus_pose.CLEARANCE
    assert max(abs(x), abs(y)) <= inner + 1e-6
    assert max(abs(x), abs(y)) >= 0.5 + corpus_pose.CLEARANCE - 0.05
    assert abs(pose["z"]) < 0.01
    assert pose["finite"] > 0.9   # walls all around, within the laser's range


def test_free_pose_finder_says_why_when_there_is_no_floor(tmp_path):
    """The block alone, no ground: no point has a floor within reach."""
    path = tmp_path / "block.world"
    path.write_text(WORLD.format(ground="", walls=""))
    pose = corpus_pose.find_free_pose(str(path))
    assert list(pose) == ["error"] and "no flat static floor" in pose["error"]


def test_grid_ranking_and_the_most_open_direction():
    points = corpus_pose.grid_points((-1.0, -1.0), (1.0, 1.0), max_count=16)
    assert len(points) == 16 and np.allclose(points.min(axis=0), -0.75)
    order = corpus_pose.rank(points, np.array([5] * 15 + [9]))
    assert order[0] == 15
    distances = np.full(corpus_pose.RING_RAYS, 1.0)
    distances[9:12] = np.inf
    assert corpus_pose.most_open(distances) == (10, corpus_pose.RING_RANGE)


def test_camera_colours_tell_grey_from_colour():
    grey = np.full((48, 64, 3), 128, np.uint8)
    grey[:24] = 90
    assert corpus_metrics.camera_summary([grey]) == (2, False)
    painted = grey.copy()
    painted[:10, :10] = (200, 40, 40)
    count, coloured = corpus_metrics.camera_summary([grey, painted])
    assert count == 3 and coloured


def test_drive_result_passes_a_good_drive_and_fails_a_stuck_one():
    good = corpus_metrics.drive_result((1.0, 1.0, math.pi / 2), (1.0, 1.39, math.pi / 2),
                                       (1.0, 1.39, math.pi / 2 + 0.97), 0.4, 1.0)
    assert good["ok"] and abs(good["forward"] - 0.39) < 1e-9
    stuck = corpus_metrics.drive_result((0, 0, 0), (0.02, 0.0, 0.0), (0.02, 0.0, 1.0), 0.4, 1.0)
    assert not stuck["ok"]


def test_refusal_line_from_a_roslaunch_log():
    log = ("\x1b[1mprocess[gazebo-2]: started\x1b[0m\n[WARN] [1.0, 0.0]: a mesh is missing\n"
           "[FATAL] [1795780951.832926, 0.000000]: gazebo: /c/w.world:3: malformed XML\n"
           "\x1b[31m=====REQUIRED process [gazebo-2] has died!\n")
    assert corpus_metrics.refusal_line(log) == "/c/w.world:3: malformed XML"
    assert corpus_metrics.warning_lines(log) == ["a mesh is missing"]
    crash = "Traceback (most recent call last):\n  File x\nImportError: cannot import name 'q'\n"
    assert corpus_metrics.refusal_line(crash) == "crash: ImportError: cannot import name 'q'"
    assert corpus_metrics.refusal_line("all well\n") is None


def test_report_has_a_row_per_world_and_a_reason_per_failure():
    reference = {"warm_s": 2.0, "cpu": 0.1, "cpu_camera": 0.4, "colours": 12}
    results = [
        {"name": "good", "loaded": True, "models": 4, "laser": 0.5, "colours": 20,
         "in_colour": True, "drive": {"ok": True}, "cold_s": 9.0, "warm_s": 3.0,
         "cpu": 0.2, "cpu_camera": 0.6},
        {"name": "refused", "loaded": False, "reason": "w.world:3: <actor> is not supported"},
        {"name": "lifted", "loaded": False, "workaround": "z_pos 0.100",
         "reason": "spawn (1, 2) is inside floor"},
    ]
    report = corpus_metrics.format_report(results, reference, "header")
    rows = [line for line in report.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) == 4   # the column names and three worlds
    assert "| good | yes | 4 | 50 % | 20, colour | ok | 9.0 / 3.0 | 2.00x (1.50x) |" in report
    assert "- refused: `w.world:3: <actor> is not supported`" in report
    assert "- lifted: `spawn (1, 2) is inside floor`" in report
    assert "1 of 3 worlds loaded unmodified." in report
    assert all(len(line) <= 400 for line in report.splitlines())
    json.dumps(results)   # what bench/corpus.py writes beside the table
