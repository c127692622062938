"""Fuel URLs found as Gazebo 11 finds them (fuel_uri, through asset_uri.resolve_uri): in the
Fuel cache (IGN_FUEL_CACHE_PATH, else ~/.ignition/fuel, then GZ_FUEL_CACHE_PATH), then in a
model folder of the same name; never downloaded. Caches of our own in tmp_path, and the
committed fixture test/fixtures/worlds/fuel/cache. No ROS."""
import os

import pytest

from tutorial_turtlebot.sim.files.asset_uri import (AssetNotFound, FuelNotCached, ModelPath,
                                                    resolve_uri)
from tutorial_turtlebot.sim.files.fuel_uri import cache_roots, parse_fuel

import unit_paths

FIXTURE_CACHE = os.path.join(unit_paths.FIXTURES, "worlds", "fuel", "cache")
CRATE = ("https://fuel.ignitionrobotics.org/1.0/OpenRobotics/models/Test_Crate/%s/files/"
         "meshes/crate.obj")


def model_path(**environ):
    """A ModelPath reading only ``environ`` (no ROS exports)."""
    return ModelPath(environ=environ, ros_exports=lambda: [])


def cache_model(root, owner, name, version, files=("meshes/a.obj",),
                host="fuel.ignitionrobotics.org"):
    """A model cached as fuel-tools caches one: root/host/owner/models/name/version, with its
    model.config and ``files``; returns the version folder."""
    folder = root / host / owner / "models" / name / str(version)
    folder.mkdir(parents=True)
    (folder / "model.config").write_text("<model><sdf version='1.6'>model.sdf</sdf></model>")
    for each in files:
        (folder / each).parent.mkdir(parents=True, exist_ok=True)
        (folder / each).write_text("# %s version %s\n" % (name, version))
    return folder


def test_fuel_urls_are_parsed_as_fuel_tools_parses_them():
    assert parse_fuel(CRATE % "tip") == ("fuel.ignitionrobotics.org", "OpenRobotics",
                                         "Test_Crate", "", "meshes/crate.obj")
    assert parse_fuel("https://fuel.gazebosim.org/openrobotics/models/Cordless%20Drill/3/"
                      "files/meshes/drill.dae")[2:] == ("Cordless Drill", "3", "meshes/drill.dae")
    assert parse_fuel("https://fuel.gazebosim.org/1.0/o/models/Box") == (
        "fuel.gazebosim.org", "o", "Box", "", None)                  # a model, the tip
    assert parse_fuel("https://fuel.gazebosim.org/1.0/o/models/Box/2")[3:] == ("2", None)
    assert parse_fuel("https://example.com/a.dae") is None


def test_the_committed_cache_gives_the_tip_and_a_named_version():
    """IGN_FUEL_CACHE_PATH is the cache Gazebo 11 reads; owner and name in another letter case
    than the cache's folders; tip is the highest version there."""
    models = model_path(IGN_FUEL_CACHE_PATH=FIXTURE_CACHE)
    folder = os.path.join(FIXTURE_CACHE, "fuel.ignitionrobotics.org", "openrobotics", "models",
                          "test_crate")
    assert resolve_uri(CRATE % "tip", "/elsewhere", models) == os.path.join(
        folder, "2", "meshes", "crate.obj")
    assert resolve_uri(CRATE % "1", "/elsewhere", models) == os.path.join(
        folder, "1", "meshes", "crate.obj")
    with pytest.raises(FuelNotCached, match="not cached"):
        resolve_uri(CRATE % "7", "/elsewhere", models)          # a version not in the cache


def test_home_cache_and_the_other_server_name(tmp_path):
    """Without IGN_FUEL_CACHE_PATH the cache is ~/.ignition/fuel; a URL of
    fuel.gazebosim.org finds a model cached under fuel.ignitionrobotics.org."""
    cached = cache_model(tmp_path / ".ignition" / "fuel", "openrobotics", "cordless drill", 4)
    uri = ("https://fuel.gazebosim.org/1.0/OpenRobotics/models/Cordless%20Drill/tip/files/"
           "meshes/a.obj")
    assert resolve_uri(uri, "/", model_path(HOME=str(tmp_path))) == str(cached / "meshes"
                                                                        / "a.obj")
    # IGN_FUEL_CACHE_PATH that is no folder: fuel-tools keeps its default, ~/.ignition/fuel
    assert cache_roots({"HOME": str(tmp_path), "IGN_FUEL_CACHE_PATH": "/no/such"}) == [
        str(tmp_path / ".ignition" / "fuel")]


def test_gz_fuel_cache_path_is_read_after_gazebo_11s_cache(tmp_path):
    cached = cache_model(tmp_path / "gz", "o", "m", 1)
    models = model_path(HOME=str(tmp_path / "home"), GZ_FUEL_CACHE_PATH=str(tmp_path / "gz"))
    uri = "https://fuel.gazebosim.org/1.0/o/models/m/1/files/meshes/a.obj"
    assert resolve_uri(uri, "/", models) == str(cached / "meshes" / "a.obj")


def test_a_model_folder_of_the_same_name_is_taken_next(tmp_path):
    (tmp_path / "models" / "Test_Table" / "meshes").mkdir(parents=True)
    (tmp_path / "models" / "Test_Table" / "meshes" / "table.obj").write_text("# table\n")
    models = model_path(HOME=str(tmp_path), GAZEBO_MODEL_PATH=str(tmp_path / "models"))
    uri = "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Test_Table/3/files/meshes/table.obj"
    assert resolve_uri(uri, "/", models) == str(tmp_path / "models" / "Test_Table" / "meshes"
                                                / "table.obj")
    # a model URL (an <include>): the cached version folder, else the model folder
    assert resolve_uri("https://fuel.gazebosim.org/1.0/OpenRobotics/models/Test_Table", "/",
                       models) == str(tmp_path / "models" / "Test_Table")


def test_not_cached_is_one_line_naming_where_it_was_searched(tmp_path):
    models = model_path(HOME=str(tmp_path), GAZEBO_MODEL_PATH=str(tmp_path / "models"))
    uri = "https://fuel.gazebosim.org/1.0/o/models/Lamp/1/files/meshes/lamp.dae"
    with pytest.raises(FuelNotCached) as caught:
        resolve_uri(uri, "/", models)
    err = caught.value
    assert err.short == uri + " not cached" and "\n" not in str(err)
    assert str(tmp_path / ".ignition" / "fuel") in err.searched
    assert "GAZEBO_MODEL_PATH" in err.searched and "nothing is downloaded" in err.searched


def test_a_version_folder_without_model_config_is_no_cached_model(tmp_path):
    folder = cache_model(tmp_path, "o", "m", 2)
    (folder / "model.config").unlink()
    with pytest.raises(FuelNotCached):
        resolve_uri("https://fuel.gazebosim.org/1.0/o/models/m/tip/files/meshes/a.obj", "/",
                    model_path(IGN_FUEL_CACHE_PATH=str(tmp_path)))


def test_a_path_out_of_the_model_and_other_web_uris_are_not_found(tmp_path):
    cache_model(tmp_path, "o", "m", 1)
    models = model_path(IGN_FUEL_CACHE_PATH=str(tmp_path))
    with pytest.raises(AssetNotFound, match="leaves the model's folder"):
        resolve_uri("https://fuel.gazebosim.org/1.0/o/models/m/1/files/../../../../x", "/", models)
    with pytest.raises(AssetNotFound, match="not a Fuel model or model file URL"):
        resolve_uri("https://example.com/meshes/a.dae", "/", models)
