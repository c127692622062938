#!/usr/bin/env python3
"""Make the peer's source tree that ``make peer`` (tools/peer/run_peer.py) runs the tests of:
ros-simulation/gazebo_ros_pkgs, branch noetic-devel, at the pinned commit PEER_COMMIT. Nothing
of it is in this repository: the tree lies in $PEER_SRC, else /work/peer/gazebo_ros_pkgs.

It comes from a git snapshot, as the session tool ``fetch`` brings it (``fetch
github:ros-simulation/gazebo_ros_pkgs`` puts a git directory in
/work/.mirror/ros-simulation+gazebo_ros_pkgs/repo); the same tree is
``git -C <that directory> archive PEER_COMMIT | tar -x -C $PEER_SRC``, or a clone checked out
at PEER_COMMIT. A file ``.peer_commit`` in it names the commit (a checkout's own HEAD does, in
one that has none).

Usage::

    python3 tools/peer/fetch_peer.py            # write the tree from the snapshot, then check it
    python3 tools/peer/fetch_peer.py --check    # only check: the commit and the files make peer
                                                # reads (PINNED: their git blob ids)

Exit status 0 when the tree is there and right, 1 otherwise (one line for each fault).
"""
import argparse
import hashlib
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "corpus"))
from fetch_corpus import copy_tree, git, git_dir, has_commit  # noqa: E402

REPO = "ros-simulation/gazebo_ros_pkgs"
PEER_COMMIT = "f9e1a4607842afa5888ef01de31cd64a1e3e297f"   # noetic-devel
DEFAULT_PEER_SRC = "/work/peer/gazebo_ros_pkgs"
DEFAULT_MIRRORS = "/work/.mirror"
STAMP = ".peer_commit"
# The files make peer reads to know the tests, with their git blob ids at PEER_COMMIT.
PINNED = {
    "gazebo_plugins/CMakeLists.txt": "786399aa74b45f3d92cc7f84a6b6939cf390a623",
    "gazebo_ros/test/CMakeLists.txt": "ba34f9c4e304a8def45840bc9af292dcfcd40652",
    "gazebo_plugins/test2/CMakeLists_tests_pkg.txt": "95c986985658ffab4e3f8e503bf5aec22d2edf16",
}
# Folders the scratch workspace copies from.
FOLDERS = ["gazebo_plugins/test", "gazebo_plugins/test2", "gazebo_plugins/scripts",
           "gazebo_ros/launch", "gazebo_ros/test"]


def peer_src():
    """The peer's source tree: $PEER_SRC, else /work/peer/gazebo_ros_pkgs."""
    return os.environ.get("PEER_SRC") or DEFAULT_PEER_SRC


def blob_id(path):
    """git's blob id of a file (``git hash-object``), without git."""
    with open(path, "rb") as handle:
        data = handle.read()
    return hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()


def checkout_commit(root):
    """The commit checked out in ``root`` when it is a git checkout, else None."""
    if not os.path.exists(os.path.join(root, ".git")):
        return None
    out = subprocess.run(["git", "-C", root, "rev-parse", "HEAD"], capture_output=True,
                         text=True)
    return out.stdout.strip() or None if out.returncode == 0 else None


def check(root):
    """[fault lines] of the tree at ``root``; [] when it is PEER_COMMIT's."""
    if not os.path.isdir(root):
        return ["%s does not exist" % root]
    faults = []
    commit = checkout_commit(root)
    try:
        with open(os.path.join(root, STAMP), encoding="utf-8") as handle:
            commit = handle.read().strip()
    except OSError:
        if commit is None:
            faults.append("%s: no %s and not a git checkout" % (root, STAMP))
    if commit is not None and commit != PEER_COMMIT:
        faults.append("%s is at commit %s, not %s" % (root, commit, PEER_COMMIT))
    for path, blob in sorted(PINNED.items()):
        full = os.path.join(root, path)
        if not os.path.isfile(full):
            faults.append("%s missing" % full)
        elif blob_id(full) != blob:
            faults.append("%s differs from %s at %s" % (full, REPO, PEER_COMMIT[:8]))
    for folder in FOLDERS:
        if not os.path.isdir(os.path.join(root, folder)):
            faults.append("%s missing" % os.path.join(root, folder))
    return faults


def how_to_make(root):
    """One line: how to make the tree at ``root``."""
    return ("make it with: python3 tools/peer/fetch_peer.py (from a snapshot of github:%s in "
            "%s), or PEER_SRC=<a checkout of %s at %s>" % (REPO, DEFAULT_MIRRORS, REPO,
                                                           PEER_COMMIT[:8]))


def executables(gdir):
    """[(mode, path)] of PEER_COMMIT's files, from the snapshot."""
    out = git(gdir, "ls-tree", "-r", "-z", PEER_COMMIT).stdout.decode("utf-8", "replace")
    return [(entry.split()[0], entry.split("\t", 1)[1]) for entry in out.split("\0")
            if "\t" in entry]


def build(root, mirrors):
    """Write PEER_COMMIT's tree into ``root`` from the snapshot; [fault lines]."""
    gdir = git_dir(mirrors, REPO)
    if gdir is None or not has_commit(gdir, PEER_COMMIT):
        return ["no snapshot of %s with commit %s in %s: fetch github:%s"
                % (REPO, PEER_COMMIT[:8], mirrors, REPO)]
    os.makedirs(root, exist_ok=True)
    absent = copy_tree(gdir, PEER_COMMIT, ".", root)
    for mode, name in executables(gdir):   # as a checkout: test nodes are run by their name
        if mode == "100755" and os.path.isfile(os.path.join(root, name)):
            os.chmod(os.path.join(root, name), 0o755)
    with open(os.path.join(root, STAMP), "w", encoding="utf-8") as handle:
        handle.write(PEER_COMMIT + "\n")
    return ["%s absent from the snapshot" % name for name in absent]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="write nothing; say what is wrong")
    parser.add_argument("--peer-src", default=None, help="the tree (default: $PEER_SRC, else %s)"
                        % DEFAULT_PEER_SRC)
    parser.add_argument("--mirrors", default=DEFAULT_MIRRORS, help="where fetch puts snapshots")
    args = parser.parse_args(argv)
    root = args.peer_src or peer_src()
    faults = [] if args.check else build(root, args.mirrors)
    faults += check(root)
    for line in faults:
        print(line)
    print("%s at %s in %s: %s" % (REPO, PEER_COMMIT[:8], root,
                                  "complete" if not faults else "%d faults (above)" % len(faults)))
    return 0 if not faults else 1


if __name__ == "__main__":
    sys.exit(main())
