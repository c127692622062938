"""Reading the files a world or a robot names (sim/file_read): regular files only, at most their
kind's size, every refusal one line; a FIFO, /dev/stdin or /dev/zero is never read (they once
froze the sim or filled its memory)."""
import os
import stat

import pytest

from tutorial_turtlebot.errors import UserError, WorldError
from tutorial_turtlebot.sim.files import file_read
from tutorial_turtlebot.sim.files.file_read import not_regular, read_file

from unit_helpers import within


def refused(path, limit=1000, what="world file"):
    with pytest.raises(WorldError) as err:
        within(10, read_file, str(path), limit, what, WorldError)
    message = str(err.value)
    assert "\n" not in message and message.startswith("%s: cannot read %s: " % (path, what))
    return message


def test_a_regular_file_and_a_link_to_one_are_read(tmp_path):
    (tmp_path / "a.world").write_bytes(b"<sdf/>")
    (tmp_path / "link.world").symlink_to(tmp_path / "a.world")
    assert read_file(str(tmp_path / "a.world"), 6, "world file") == b"<sdf/>"
    assert read_file(str(tmp_path / "link.world"), 6, "world file") == b"<sdf/>"
    assert not_regular(str(tmp_path / "link.world")) is None


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "pipe.world"
    os.mkfifo(str(fifo))
    assert refused(fifo).endswith("it is a FIFO, not a regular file")
    (tmp_path / "link.world").symlink_to(fifo)
    assert refused(tmp_path / "link.world").endswith("it is a FIFO, not a regular file")


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/null", "/dev/stdin"])
def test_devices_are_refused(tmp_path, device):
    if not os.path.exists(device) or stat.S_ISREG(os.stat(device).st_mode):
        pytest.skip("no %s here, or a regular file (stdin from a file)" % device)
    link = tmp_path / "model.config"
    link.symlink_to(device)
    assert "not a regular file" in refused(link, what="model.config")


def test_a_directory_and_a_missing_file_are_refused(tmp_path):
    assert refused(tmp_path).endswith("it is a directory, not a regular file")
    assert refused(tmp_path / "missing.world").endswith("No such file or directory")


def test_a_file_larger_than_its_kind_allows_is_refused(tmp_path):
    (tmp_path / "big.world").write_bytes(b"x" * 1001)
    assert refused(tmp_path / "big.world").endswith(
        "it is 1001 bytes, more than the 1000 allowed")
    (tmp_path / "ok.world").write_bytes(b"x" * 1000)
    assert read_file(str(tmp_path / "ok.world"), 1000, "world file") == b"x" * 1000


def test_a_file_that_grows_while_it_is_read_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "growing.world"
    path.write_bytes(b"x" * 10)
    real_read = os.read

    def growing(fd, count):      # the file gains bytes after fstat saw 10
        chunk = real_read(fd, count)
        with open(str(path), "ab") as f:
            f.write(b"y" * 100)
        return chunk
    monkeypatch.setattr(file_read.os, "read", growing)
    assert refused(path, limit=50).endswith("it grew past the 50 bytes allowed while it was read")


def test_the_default_error_is_a_user_error(tmp_path):
    with pytest.raises(UserError):
        read_file(str(tmp_path), 10, "URDF file")


def test_each_kind_has_its_bound():
    assert file_read.MAX_MODEL_CONFIG_BYTES == 1_000_000
    assert (file_read.MAX_MODEL_CONFIG_BYTES < file_read.MAX_XML_FILE_BYTES
            < file_read.MAX_MESH_SIDE_FILE_BYTES < file_read.MAX_MESH_FILE_BYTES)
