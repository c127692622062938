"""Finding the files a world or robot names (asset_uri): model://, package://, file://, paths."""
import os

import pytest

from tutorial_turtlebot.sim.files.asset_uri import (PACKAGE_MODELS, AssetError, AssetNotFound,
                                                    ModelLeftOut, ModelPath,
                                                    _ros_exported_model_paths, case_mismatch,
                                                    model_sdf_file, resolve_uri, split_uri)


def make_model(folder, name, versions=(("1.6", "model.sdf"),)):
    """A Gazebo model folder ``folder/name`` whose model.config names ``versions``."""
    path = folder / name
    path.mkdir(parents=True)
    entries = "".join('<sdf version="%s">%s</sdf>' % v for v in versions)
    (path / "model.config").write_text('<?xml version="1.0"?><model><name>%s</name>%s</model>'
                                       % (name, entries))
    for _, file in versions:
        (path / file).write_text('<sdf version="1.6"><model name="%s"/></sdf>' % name)
    return path


def no_ros():
    return []


def test_split_uri():
    assert split_uri("model://a/b.dae") == ("model", "a/b.dae")
    assert split_uri("package://p/m.stl") == ("package", "p/m.stl")
    assert split_uri("file:///abs/x.obj") == ("file", "/abs/x.obj")
    assert split_uri("meshes/x.obj") == ("", "meshes/x.obj")


def test_gazebo_model_path_is_searched_in_order_before_the_package(tmp_path):
    first, second = tmp_path / "first", tmp_path / "second"
    make_model(first, "table")
    make_model(second, "table")
    make_model(second, "chair")
    path = ModelPath({"GAZEBO_MODEL_PATH": "%s::%s" % (first, second)}, ros_exports=no_ros)
    assert resolve_uri("model://table", "/", path) == str(first / "table")
    assert resolve_uri("model://chair/model.sdf", "/", path) == str(second / "chair" / "model.sdf")
    # Gazebo's stock models come with the package, with no path set
    bare = ModelPath({}, ros_exports=no_ros)
    assert resolve_uri("model://ground_plane", "/", bare) == os.path.join(PACKAGE_MODELS,
                                                                          "ground_plane")
    assert os.path.isdir(resolve_uri("model://sun", "/", bare))


def test_a_missing_model_names_the_uri_and_every_folder_searched(tmp_path):
    path = ModelPath({"GAZEBO_MODEL_PATH": str(tmp_path), "HOME": "/home/me"},
                     ros_exports=lambda: ["/opt/pkg/models"])
    with pytest.raises(AssetError) as err:
        resolve_uri("model://cafe_table", "/", path)
    message = str(err.value)
    assert "\n" not in message and message.startswith("model://cafe_table not found")
    for folder in (str(tmp_path), "/opt/pkg/models", "/home/me/.gazebo/models", PACKAGE_MODELS):
        assert folder in message


def test_ros_exports_are_read_only_when_needed(tmp_path):
    calls = []

    def exports():
        calls.append(1)
        return [str(tmp_path / "exported")]
    make_model(tmp_path / "env", "a")
    make_model(tmp_path / "exported", "b")
    path = ModelPath({"GAZEBO_MODEL_PATH": str(tmp_path / "env")}, ros_exports=exports)
    assert resolve_uri("model://a", "/", path).endswith("a") and not calls
    assert resolve_uri("model://b", "/", path) == str(tmp_path / "exported" / "b")
    assert resolve_uri("model://b/model.sdf", "/", path) and calls == [1]


def test_ros_packages_export_their_model_folders(tmp_path, monkeypatch):
    package = tmp_path / "my_worlds"
    make_model(package / "models", "arena")
    (package / "package.xml").write_text(
        '<?xml version="1.0"?><package format="2"><name>my_worlds</name><version>1.0.0'
        '</version><description>d</description><maintainer email="a@example.com">a</maintainer>'
        '<license>BSD</license><export><gazebo_ros gazebo_model_path="${prefix}/models"/>'
        '</export></package>')
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    assert _ros_exported_model_paths() == [str(package / "models")]
    assert resolve_uri("package://my_worlds/models/arena", "/") == str(package / "models" / "arena")
    with pytest.raises(AssetError, match="no ROS package 'nowhere'"):
        resolve_uri("package://nowhere/m.stl", "/")


def test_file_uris_and_paths_are_relative_to_the_naming_file(tmp_path):
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "a.stl").write_bytes(b"")
    expected = str(tmp_path / "meshes" / "a.stl")
    assert resolve_uri("meshes/a.stl", str(tmp_path)) == expected
    assert resolve_uri("file://meshes/a.stl", str(tmp_path)) == expected
    assert resolve_uri("file://" + expected, "/elsewhere") == expected
    with pytest.raises(AssetError, match="b.stl not found"):
        resolve_uri("meshes/b.stl", str(tmp_path))
    with pytest.raises(AssetError, match="only model://"):
        resolve_uri("ftp://example.com/a.dae", str(tmp_path))
    with pytest.raises(AssetNotFound, match="not a Fuel model or model file URL"):
        resolve_uri("http://example.com/a.dae", str(tmp_path))   # Gazebo: the mesh left out


def test_model_config_picks_the_newest_sdf_gazebo_reads(tmp_path):
    folder = make_model(tmp_path, "m", (("1.4", "model-1_4.sdf"), ("1.6", "model.sdf"),
                                        ("1.10", "future.sdf")))
    assert model_sdf_file(str(folder)) == str(folder / "model.sdf")


def test_without_a_version_it_reads_the_first_entry_as_sdformat_9_does(tmp_path):
    """sdformat 9's getBestSupportedModelVersion starts from the first <sdf> and keeps it when
    no entry has a version up to 1.7 (one too new is "ignored", and then taken all the same)."""
    folder = tmp_path / "m"
    folder.mkdir()
    (folder / "x.sdf").write_text('<sdf version="1.6"><model name="m"/></sdf>')
    (folder / "y.sdf").write_text('<sdf version="1.6"><model name="m"/></sdf>')
    (folder / "model.config").write_text('<model><sdf version="2.0">x.sdf</sdf>'
                                         '<sdf version="1.9">y.sdf</sdf></model>')
    assert model_sdf_file(str(folder)) == str(folder / "x.sdf")


def test_a_model_config_naming_no_file_leaves_the_model_out(tmp_path):
    """Gazebo cannot take a file from these: it leaves the model out (a warning, the world
    loads: test_world_includes.py)."""
    folder = tmp_path / "m"
    folder.mkdir()
    for config in ('<model><name>m</name></model>', '<model><sdf version="1.6"> </sdf></model>',
                   '<package><sdf version="1.6">m.sdf</sdf></package>'):
        (folder / "model.config").write_text(config)
        with pytest.raises(ModelLeftOut, match="model.config:1: .*Gazebo leaves the model out"):
            model_sdf_file(str(folder))
    (folder / "model.config").unlink()
    with pytest.raises(ModelLeftOut, match="has no model.config"):
        model_sdf_file(str(folder))
    (folder / "manifest.xml").write_text('<model><sdf version="1.5">m.sdf</sdf></model>')
    (folder / "m.sdf").write_text('<sdf version="1.5"><model name="m"/></sdf>')
    assert model_sdf_file(str(folder)) == str(folder / "m.sdf")     # sdformat 9 reads it


@pytest.mark.parametrize("version", ["-1", "1.x", "", "0", "0.0", "1.-6", "v1.6", "1.6.0.1",
                                     "1" * 5000, "1." + "6" * 5000])
def test_a_version_that_is_no_version_loses_to_a_real_one(tmp_path, version):
    """Gazebo reads these as 0.0.0, which never wins over a real version; alone, the first
    entry is taken (as it is without a version)."""
    folder = make_model(tmp_path, "m", ((version, "odd.sdf"),))
    assert model_sdf_file(str(folder)) == str(folder / "odd.sdf")
    folder = make_model(tmp_path / "two", "m", ((version, "odd.sdf"), ("1.5", "model.sdf")))
    assert model_sdf_file(str(folder)) == str(folder / "model.sdf")


def test_versions_are_compared_as_numbers(tmp_path):
    folder = make_model(tmp_path, "m", (("1.6.1", "patch.sdf"), ("1.6", "model.sdf"),
                                        ("1.10", "future.sdf")))
    assert model_sdf_file(str(folder)) == str(folder / "patch.sdf")


# --- model.config read as leniently as Gazebo's TinyXML reads it --------------------------------

LENIENT = {
    "a bare & in the description": '<description>rail & closed curtain</description>',
    "an entity TinyXML does not know": '<description>caf&eacute; &nbsp; &#xe9;</description>',
    "a < that starts no tag": '<description>1 < 2 and 3 > 2</description>',
    "an unquoted attribute": '<author email=a@b.c>x</author>',
    "a DOCTYPE": '',
    "a control character": '<description>bell\x07</description>',
}


@pytest.mark.parametrize("case", sorted(LENIENT))
def test_model_config_is_read_as_leniently_as_tinyxml_reads_it(tmp_path, case):
    folder = tmp_path / "m"
    folder.mkdir()
    doctype = '<!DOCTYPE model [<!ENTITY x "y">]>\n' if case == "a DOCTYPE" else ""
    (folder / "model.config").write_bytes(
        ('<?xml version="1.0"?>\n%s<model>\n<name>m</name>\n%s\n<sdf version=1.6>model.sdf'
         '</sdf>\n</model>\n' % (doctype, LENIENT[case])).encode().replace(b"\\x07", b"\x07"))
    (folder / "model.sdf").write_text('<sdf version="1.6"><model name="m"/></sdf>')
    assert model_sdf_file(str(folder)) == str(folder / "model.sdf")


def test_a_model_config_in_latin_1_is_read(tmp_path):
    folder = tmp_path / "m"
    folder.mkdir()
    (folder / "model.config").write_bytes(b'<?xml version="1.0" encoding="UTF-8"?><model>'
                                          b'<description>caf\xe9 & bar</description>'
                                          b'<sdf version="1.6">model.sdf</sdf></model>')
    (folder / "model.sdf").write_text('<sdf version="1.6"><model name="m"/></sdf>')
    assert model_sdf_file(str(folder)) == str(folder / "model.sdf")


def test_what_tinyxml_cannot_read_leaves_the_model_out_in_one_line(tmp_path):
    """A mismatched end tag stops TinyXML too (TIXML_ERROR_READING_END_TAG)."""
    folder = tmp_path / "m"
    folder.mkdir()
    (folder / "model.config").write_text('<model>\n<sdf version="1.6">model.sdf</model>\n')
    with pytest.raises(ModelLeftOut) as err:
        model_sdf_file(str(folder))
    message = str(err.value)
    assert "\n" not in message and "model.config:2: malformed XML: mismatched tag" in message
    assert "Gazebo (TinyXML) cannot read it either: the model is left out" in message


# --- Gazebo's order for relative file:// URIs and paths ------------------------------------------

def mesh_in(folder, relative="models/x/meshes/y.dae"):
    path = folder / relative
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"")
    return str(path)


@pytest.fixture
def places(tmp_path, monkeypatch):
    """Four folders, one per step of the search, and a working directory of its own."""
    folders = {k: tmp_path / k for k in ("model", "cwd", "resource", "model_path")}
    for folder in folders.values():
        folder.mkdir()
    monkeypatch.chdir(folders["cwd"])
    env = {"GAZEBO_RESOURCE_PATH": "%s:%s" % (tmp_path / "unset", folders["resource"]),
           "GAZEBO_MODEL_PATH": str(folders["model_path"])}
    return folders, ModelPath(env, ros_exports=no_ros)


@pytest.mark.parametrize("uri", ["file://models/x/meshes/y.dae", "models/x/meshes/y.dae"])
def test_a_relative_uri_is_searched_in_gazebos_order(places, uri):
    """The naming file's folder, the working directory, GAZEBO_RESOURCE_PATH, the model path:
    each step is taken when the ones before it miss, and loses to them when they hit."""
    folders, path = places
    base = str(folders["model"])
    for k in ("model_path", "resource", "cwd", "model"):    # a hit one step earlier each time
        expected = mesh_in(folders[k])
        assert resolve_uri(uri, base, path) == expected
    for k in ("model", "cwd", "resource", "model_path"):
        os.remove(str(folders[k] / "models/x/meshes/y.dae"))
    # and each alone, the others missing
    for k in ("model_path", "resource", "cwd"):
        expected = mesh_in(folders[k])
        assert resolve_uri(uri, base, path) == expected
        os.remove(expected)


def test_a_relative_uri_found_nowhere_names_every_place(places):
    folders, path = places
    with pytest.raises(AssetNotFound) as err:
        resolve_uri("file://models/x/meshes/y.dae", str(folders["model"]), path)
    message = str(err.value)
    assert "\n" not in message and message.startswith("file://models/x/meshes/y.dae not found")
    for folder in folders.values():
        assert str(folder) in message
    assert "GAZEBO_RESOURCE_PATH (" in message and "GAZEBO_MODEL_PATH (" in message


def test_a_name_differing_only_in_case_is_not_taken_but_named(tmp_path):
    real = mesh_in(tmp_path, "meshes/mailbox.dae")
    assert case_mismatch(str(tmp_path / "Meshes" / "Mailbox.DAE")) == real
    assert case_mismatch(str(tmp_path / "meshes" / "other.dae")) is None
    assert case_mismatch(real) is None                    # it exists: no mismatch
    with pytest.raises(AssetNotFound) as err:
        resolve_uri("meshes/Mailbox.DAE", str(tmp_path), ModelPath({}, ros_exports=no_ros))
    assert "%s exists, whose name differs only in letter case" % real in str(err.value)
    with pytest.raises(AssetNotFound) as err:
        resolve_uri("file://" + str(tmp_path / "meshes" / "Mailbox.DAE"), "/")
    assert "differs only in letter case" in str(err.value)


def test_a_missing_model_says_where_gazebos_models_are(tmp_path):
    path = ModelPath({"GAZEBO_MODEL_PATH": str(tmp_path)}, ros_exports=no_ros)
    with pytest.raises(AssetNotFound) as err:
        resolve_uri("model://mailbox", "/", path)
    assert ("https://github.com/osrf/gazebo_models: download it and add its folder to "
            "GAZEBO_MODEL_PATH") in str(err.value)
    make_model(tmp_path, "mailbox")
    with pytest.raises(AssetNotFound) as err:
        resolve_uri("model://MailBox/model.sdf", "/", path)
    assert "%s exists, whose name differs only in letter case" % (tmp_path / "mailbox"
                                                                  / "model.sdf") in str(err.value)
