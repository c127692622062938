#!/usr/bin/env python3
"""Re-create the corpus of public Gazebo worlds that ``make corpus`` (bench/corpus.py) runs over,
from tools/corpus/manifest.json. Nothing of the corpus is in this repository: the manifest holds
only facts (where each file comes from, at which commit, and the world file's SHA-256).

The files come from git snapshots of public repositories, as the session tool ``fetch`` brings
them (``fetch github:OWNER/NAME`` puts a git directory in ``/work/.mirror/OWNER+NAME/repo``).
A repository too large to fetch (Gazebo classic's own, for its example worlds) is marked
``"via": "read_file"``: read that one file with the session tool ``read_file`` (repo, path and
commit as the manifest gives them) and write its text to the destination this script names.

Layout of the corpus (``$TUTORIAL_TURTLEBOT_CORPUS``, else /work/corpus), one folder a world::

    NAME/WORLD_FILE           the world file, as its repository has it
    NAME/models/MODEL/        each model folder it names (model://MODEL), found through
                              GAZEBO_MODEL_PATH=NAME/models
    NAME/DEST/                extra folders (meshes a world names by file://), on
                              GAZEBO_RESOURCE_PATH when the manifest says so

Usage::

    python3 tools/corpus/fetch_corpus.py            # write what the snapshots hold; list the rest
    python3 tools/corpus/fetch_corpus.py --check    # only say what is missing or differs
    python3 tools/corpus/fetch_corpus.py --resolve REPO PATH [--also REPO ...]
        # for a new manifest entry: the model folders a world names (model://), looked for in
        # its own repository, then in each --also repository, then in osrf/gazebo_models

Exit status 0 when the corpus is complete, 1 when something is missing (listed, one line each).
"""
import argparse
import hashlib
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
MANIFEST = os.path.join(HERE, "manifest.json")
DEFAULT_CORPUS = "/work/corpus"
DEFAULT_MIRRORS = "/work/.mirror"
MODELS_REPO = "osrf/gazebo_models"   # Gazebo's online model collection, last resort
HEX40 = re.compile(r"^[0-9a-f]{40}$")
NAME = re.compile(r"^[a-z0-9][a-z0-9_]*$")
MODEL_URI = re.compile(r"model://([^/<>\"'\s]+)")
SCANNED = (".world", ".sdf", ".material", ".urdf", ".xacro", ".model")   # files with model:// in


class ManifestError(ValueError):
    """The manifest is not what this script and bench/corpus.py expect (one line)."""


def corpus_root():
    """The corpus folder: $TUTORIAL_TURTLEBOT_CORPUS, else /work/corpus."""
    return os.environ.get("TUTORIAL_TURTLEBOT_CORPUS") or DEFAULT_CORPUS


def load_manifest(path=MANIFEST):
    """The manifest as a dict, checked (ManifestError naming the first fault)."""
    with open(path, encoding="utf-8") as handle:
        manifest = json.load(handle)
    check_manifest(manifest)
    return manifest


def check_manifest(manifest):
    """Raise ManifestError unless every world names its repository, a 40-hex commit, a path
    and the file's SHA-256, and its model folders and extra folders come from repositories of
    'repos' (one commit each)."""
    repos = manifest.get("repos")
    if not isinstance(repos, dict) or not repos:
        raise ManifestError("manifest: 'repos' must map owner/name to a commit")
    for repo, commit in repos.items():
        if repo.count("/") != 1 or not HEX40.match(str(commit)):
            raise ManifestError("manifest: repo %r needs a 40-hex commit, got %r" % (repo, commit))
    names = set()
    for world in manifest.get("worlds", []):
        name = world.get("name", "")
        if not NAME.match(name) or name in names:
            raise ManifestError("manifest: world name %r is not a new lower-case name" % name)
        names.add(name)
        repo = world.get("repo", "")
        if repo.count("/") != 1 or not HEX40.match(str(world.get("commit"))):
            raise ManifestError("manifest: %s needs a repo and a 40-hex commit" % name)
        if not world.get("path") or not re.match(r"^[0-9a-f]{64}$", world.get("sha256", "")):
            raise ManifestError("manifest: %s needs a path and the file's sha256" % name)
        for model, source in world.get("models", {}).items():
            if source.get("repo") not in repos or not source.get("path"):
                raise ManifestError("manifest: %s: model %r needs a known repo and a path"
                                    % (name, model))
        for dest, source in world.get("extra", {}).items():
            if dest.startswith(("/", "..")) or source.get("repo") not in repos:
                raise ManifestError("manifest: %s: extra %r needs a relative folder and a known "
                                    "repo" % (name, dest))
    if not names:
        raise ManifestError("manifest: no worlds")


def world_folder(root, world):
    """The corpus folder of one manifest world."""
    return os.path.join(root, world["name"])


def world_file(root, world):
    """Where the world file of one manifest world lies in the corpus."""
    return os.path.join(world_folder(root, world), os.path.basename(world["path"]))


def world_env(root, world):
    """{GAZEBO_MODEL_PATH: ..., GAZEBO_RESOURCE_PATH: ...} for one world (absolute folders)."""
    folder = world_folder(root, world)
    env = {"GAZEBO_MODEL_PATH": os.path.join(folder, world.get("model_path", "models"))}
    if world.get("resource_path"):
        env["GAZEBO_RESOURCE_PATH"] = os.path.join(folder, world["resource_path"])
    return env


def model_names(text):
    """The model folder names a file's text points at (model://NAME/...), sorted."""
    return sorted(set(MODEL_URI.findall(text)))


def sha256_file(path):
    with open(path, "rb") as handle:
        return hashlib.sha256(handle.read()).hexdigest()


# --- git snapshots ------------------------------------------------------------------------------

def git_dir(mirrors, repo):
    """The git directory of ``repo``'s snapshot under ``mirrors``, or None."""
    base = os.path.join(mirrors, repo.replace("/", "+"), "repo")
    for candidate in (os.path.join(base, ".git"), base):
        if os.path.isfile(os.path.join(candidate, "HEAD")):
            return candidate
    return None


def git(gdir, *args, data=None):
    return subprocess.run(["git", "--git-dir", gdir] + list(args), input=data,
                          capture_output=True, check=False)


def has_commit(gdir, commit):
    return git(gdir, "cat-file", "-e", commit + "^{commit}").returncode == 0


def tree_files(gdir, commit, path):
    """[(blob id, path)] of the files under ``path`` at ``commit`` (a file: itself)."""
    out = git(gdir, "ls-tree", "-r", "-z", commit, "--", path).stdout.decode("utf-8", "replace")
    files = []
    for entry in out.split("\0"):
        if "\t" in entry:
            meta, name = entry.split("\t", 1)
            kind, blob = meta.split()[1:3]
            if kind == "blob":
                files.append((blob, name))
    return files


def read_blobs(gdir, blobs):
    """{blob id: bytes or None (absent from the snapshot)} through one git cat-file --batch."""
    if not blobs:
        return {}
    out = git(gdir, "cat-file", "--batch", data="".join(b + "\n" for b in blobs).encode()).stdout
    found, pos = {}, 0
    for blob in blobs:
        end = out.index(b"\n", pos)
        header = out[pos:end].split()
        pos = end + 1
        if len(header) == 2 and header[1] == b"missing":
            found[blob] = None
            continue
        size = int(header[2])
        found[blob] = out[pos:pos + size]
        pos += size + 1
    return found


def copy_tree(gdir, commit, path, dest):
    """Write the files under ``path`` at ``commit`` into ``dest`` (``path`` itself becomes
    ``dest``); return the repository paths absent from the snapshot (files of 4 MiB and more)."""
    files = tree_files(gdir, commit, path)
    contents = read_blobs(gdir, [blob for blob, _ in files])
    absent = []
    for blob, name in files:
        data = contents.get(blob)
        if data is None:
            absent.append(name)
            continue
        rel = os.path.relpath(name, path) if name != path else os.path.basename(name)
        target = dest if name == path else os.path.join(dest, rel)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as handle:
            handle.write(data)
    return absent


# --- build and check ----------------------------------------------------------------------------

def build(manifest, root, mirrors, write=True, out=sys.stdout):
    """Write (or with ``write`` false only check) every world of the manifest into ``root``;
    print one line for each thing missing; return how many there are."""
    missing = 0
    commits = manifest["repos"]

    def say(line):
        nonlocal missing
        missing += 1
        print(line, file=out)

    for world in manifest["worlds"]:
        folder = world_folder(root, world)
        target = world_file(root, world)
        repo, commit = world["repo"], world["commit"]
        gdir = git_dir(mirrors, repo)
        if write and world.get("via") != "read_file" and gdir and has_commit(gdir, commit):
            for name in copy_tree(gdir, commit, world["path"], target):
                say("%s: %s absent from the snapshot of %s" % (world["name"], name, repo))
        if not os.path.isfile(target):
            how = ("read_file repo=%s path=%s commit=%s, write its text to %s"
                   % (repo, world["path"], commit, target)
                   if world.get("via") == "read_file"
                   else "fetch github:%s (commit %s)" % (repo, commit))
            say("%s: world file missing: %s" % (world["name"], how))
        elif sha256_file(target) != world["sha256"]:
            say("%s: %s differs from the manifest's sha256" % (world["name"], target))
        sources = [(os.path.join("models", model), src)
                   for model, src in world.get("models", {}).items()]
        sources += list(world.get("extra", {}).items())
        for dest, src in sources:
            target_dir = os.path.join(folder, dest)
            repo, commit = src["repo"], commits[src["repo"]]
            gdir = git_dir(mirrors, repo)
            if write and not os.path.isdir(target_dir) and gdir and has_commit(gdir, commit):
                for name in copy_tree(gdir, commit, src["path"], target_dir):
                    say("%s: %s absent from the snapshot of %s" % (world["name"], name, repo))
            if not os.path.isdir(target_dir):
                say("%s: %s missing: fetch github:%s (commit %s), folder %s"
                    % (world["name"], dest, repo, commit, src["path"]))
    return missing


# --- resolving a new world's models -------------------------------------------------------------

def model_candidates(paths, name):
    """Folders named ``name`` among a tree's file ``paths`` that are model folders: they hold a
    model.config, or folders below them do (a folder of models, model://A/B)."""
    found = set()
    for path in paths:
        parts = path.split("/")
        if parts[-1] != "model.config":
            continue
        for i, part in enumerate(parts[:-1]):
            if part == name:
                found.add("/".join(parts[:i + 1]))
    return sorted(found)


def closest(candidates, near):
    """The candidate folder sharing the longest leading path with ``near``, then the shortest."""
    def key(folder):
        common = os.path.commonprefix([folder.split("/"), near.split("/")])
        return (-len(common), folder.count("/"), folder)
    return min(candidates, key=key) if candidates else None


def resolve(world_text, world_path, sources, read_text):
    """({model name: (repo, folder)}, [names found nowhere]) for a world's text: every
    model://NAME it names and, in turn, those named in the text files of the folders found.
    ``sources``: [(repo, [file paths of its tree])], searched in order; ``read_text(repo,
    folder)``: the concatenated text of a folder's SDF, world, URDF and material files."""
    found, unresolved = {}, []
    queue = model_names(world_text)
    while queue:
        name = queue.pop(0)
        if name in found or name in unresolved:
            continue
        for repo, paths in sources:
            folder = closest(model_candidates(paths, name), world_path if repo == sources[0][0]
                             else "")
            if folder:
                found[name] = (repo, folder)
                queue.extend(model_names(read_text(repo, folder)))
                break
        else:
            unresolved.append(name)
    return found, unresolved


def resolve_command(args, manifest):
    commits = manifest["repos"]
    repos = [args.repo] + list(args.also) + [MODELS_REPO]
    trees = {}
    for repo in repos:
        gdir = git_dir(args.mirrors, repo)
        if gdir is None and (repo != args.repo or not args.file):
            sys.exit("no snapshot of %s in %s: fetch github:%s" % (repo, args.mirrors, repo))
        if gdir is not None:
            commit = commits.get(repo) or git(gdir, "rev-parse", "HEAD").stdout.decode().strip()
            trees[repo] = (gdir, commit)
    repos = [repo for repo in repos if repo in trees]

    def read_text(repo, folder):
        gdir, commit = trees[repo]
        files = [(b, p) for b, p in tree_files(gdir, commit, folder) if p.endswith(SCANNED)]
        blobs = read_blobs(gdir, [b for b, _ in files])
        return "\n".join((blobs[b] or b"").decode("utf-8", "replace") for b, _ in files)

    if args.file:
        with open(args.file, encoding="utf-8") as handle:
            text = handle.read()
    else:
        gdir, commit = trees[args.repo]
        text = read_text(args.repo, args.path)
    sources = [(repo, [p for _, p in tree_files(*trees[repo], ".")]) for repo in repos]
    if args.repo not in trees:   # the world's own repository has no snapshot: none is nearest
        sources.insert(0, (args.repo, []))
    found, unresolved = resolve(text, args.path, sources, read_text)
    print(json.dumps({"commits": {r: trees[r][1] for r in repos},
                      "models": {n: {"repo": r, "path": p} for n, (r, p) in sorted(found.items())},
                      "unresolved": unresolved}, indent=2))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="write nothing; list what is missing")
    parser.add_argument("--corpus", default=None, help="the corpus folder (default: %s or "
                        "$TUTORIAL_TURTLEBOT_CORPUS)" % DEFAULT_CORPUS)
    parser.add_argument("--mirrors", default=DEFAULT_MIRRORS, help="where fetch puts snapshots")
    parser.add_argument("--manifest", default=MANIFEST)
    parser.add_argument("--resolve", nargs=2, metavar=("REPO", "PATH"),
                        help="list the model folders of a world at PATH in REPO's snapshot")
    parser.add_argument("--file", help="with --resolve: read the world from this file instead")
    parser.add_argument("--also", action="append", default=[], help="with --resolve: another "
                        "repository to look for models in (before osrf/gazebo_models)")
    args = parser.parse_args(argv)
    if args.resolve:
        args.repo, args.path = args.resolve
        try:
            manifest = load_manifest(args.manifest)
        except (OSError, ManifestError):
            manifest = {"repos": {}}
        resolve_command(args, manifest)
        return 0
    manifest = load_manifest(args.manifest)
    root = args.corpus or corpus_root()
    missing = build(manifest, root, args.mirrors, write=not args.check)
    worlds = len(manifest["worlds"])
    print("%d worlds in %s: %s" % (worlds, root, "complete" if not missing
                                   else "%d things missing (above)" % missing))
    return 0 if not missing else 1


if __name__ == "__main__":
    sys.exit(main())
