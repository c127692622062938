"""Where Gazebo finds the files a world or a robot names: ``model://``, ``package://``, ``file://``.

No ROS node and no pybullet here; ``package://`` asks rospkg (ROS_PACKAGE_PATH), as Gazebo's
ROS plugins do.

- ``model://NAME/rest`` is looked up in each folder of the model path, first match wins:
  ``GAZEBO_MODEL_PATH`` (colon-separated), then ``~/.gazebo/models``, then this package's own
  ``models/`` (Gazebo's stock ``ground_plane`` and ``sun``, which come with every Gazebo), then
  the ``gazebo_model_path`` that ROS packages export for gazebo_ros in their package.xml
  (``<export><gazebo_ros gazebo_model_path="${prefix}/models"/></export>``). Those exports come
  last because reading them means reading every package's manifest (about 0.1 s), which a
  world of stock models never needs.
- A model folder holds ``model.config`` (or the older ``manifest.xml``), whose ``<sdf
  version="X">file</sdf>`` entries name one SDF file per version. Read as Gazebo 11 reads it
  (sdformat 9's getModelFilePath, with TinyXML 2.6): only those entries matter, and the text is
  read as leniently as TinyXML reads it (``read_model_config``: a bare ``&``, an unknown entity,
  an unquoted attribute value, a DOCTYPE, control characters). The highest version up to 1.7 is
  taken; if no entry has such a version (none, "-1", "1.x", "2.0"), the first ``<sdf>`` entry
  is. A folder without model.config, a model.config that is still not XML or that names no file
  is ``ModelLeftOut``: Gazebo leaves the model out and loads the rest, and so does the world
  loader. model.config and the SDF file must be regular files (file_read), model.config at most
  file_read.MAX_MODEL_CONFIG_BYTES: anything else is refused.
- ``package://PKG/rest`` is PKG's folder from rospkg, else a model folder called PKG.
- ``http://`` and ``https://`` URIs are Fuel URLs, read from the Fuel cache alone (fuel_uri).
- ``file://path`` and a bare path are absolute, or relative. A relative one is looked for as
  Gazebo looks: in the folder of the file that names it (the model's folder), then the working
  directory, then each folder of ``GAZEBO_RESOURCE_PATH`` (colon-separated), then the model
  path above; first match wins.
Every failure is an ``AssetError`` of one line naming the URI and where it was looked for; a
file or model that is not there is an ``AssetNotFound``, which names a file whose name differs
only in letter case (Gazebo on Linux does not take it either) and, for ``model://``, where
Gazebo's online models can be had.
"""
import os
import re
from typing import Callable, Iterable, List, Optional, Sequence, Tuple

from ...errors import UserError, WorldError
from . import xml_reader
from .file_read import MAX_MODEL_CONFIG_BYTES, not_regular, read_file
from .fuel_uri import fuel_file, is_web_uri, searched_line
from ...package_data import data_dir

PACKAGE_MODELS = data_dir("models")
USER_MODELS = os.path.join("~", ".gazebo", "models")
MAX_SDF_VERSION = (1, 7)      # the newest SDF version Gazebo 11 (libsdformat 9) reads


class AssetError(WorldError):
    """A file named by a URI cannot be found or read; one line naming the URI and the search."""


class AssetNotFound(AssetError):
    """The file or model folder a URI names is in none of the places searched (a world loads
    without it, as in Gazebo: world_sdf makes it a warning). ``str(err)`` names every folder
    searched; ``short`` is the same line without them, and ``searched`` the folders alone (a
    world's loader says them once, however many URIs are missing)."""

    def __init__(self, message: str, short: str = "", searched: str = ""):
        super().__init__(message)
        self.short = short or message
        self.searched = searched


class FuelNotCached(AssetNotFound):
    """A Fuel URL whose file is neither in the Fuel cache nor in a model folder of its name
    (Gazebo 11 loads the world without it; world_sdf sums such warnings up)."""


class ModelLeftOut(AssetNotFound):
    """A model folder Gazebo finds but cannot take a file from: no model.config, a model.config
    that is not XML even to TinyXML, or one that names no SDF file (a world loads without the
    model, as in Gazebo: world_sdf makes it a warning)."""


# Gazebo 11 fetches a model:// it cannot find from its online model database; those models
# (mailbox, cafe_table, ...) are the gazebo_models repository. Said in the not-found line.
MODEL_DATABASE_HINT = ("Gazebo's online models (mailbox, cafe_table ...) are in "
                       "https://github.com/osrf/gazebo_models: download it and add its folder "
                       "to GAZEBO_MODEL_PATH")


def case_mismatch(path: str) -> Optional[str]:
    """The existing path that differs from the missing ``path`` only in letter case (the first
    in sorted order at each level); None if there is none."""
    head, missing = os.path.normpath(path), []
    while not os.path.lexists(head):
        head, tail = os.path.split(head)
        if not tail:
            return None
        missing.append(tail)
    for part in reversed(missing):
        try:
            names = sorted(n for n in os.listdir(head) if n.lower() == part.lower())
        except OSError:
            return None
        if not names:
            return None
        head = os.path.join(head, names[0])
    return head if missing else None


def _case_note(candidates: Iterable[str], brief: bool = False) -> str:
    """"; X exists, whose name differs only in letter case (...)" for the first of the missing
    ``candidates`` that has such a twin; "" if none has. ``brief``: without the "(...)"."""
    for candidate in candidates:
        twin = case_mismatch(candidate)
        if twin is not None:
            if brief:
                return "; %s exists (its name differs in letter case)" % twin
            return ("; %s exists, whose name differs only in letter case (file names are "
                    "case-sensitive, as in Gazebo on Linux: fix the URI or the file name)"
                    % twin)
    return ""


def _ros_exported_model_paths() -> List[str]:
    """The ``gazebo_model_path`` folders that ROS packages on ROS_PACKAGE_PATH export for
    gazebo_ros (what gazebo_ros' launch adds to GAZEBO_MODEL_PATH); [] without rospkg."""
    try:
        import rospkg
    except ImportError:
        return []
    rospack = rospkg.RosPack()
    paths = []
    try:
        packages = rospack.list()
    except Exception:  # noqa: BLE001 - an unreadable ROS_PACKAGE_PATH adds nothing
        return []
    for package in sorted(packages):
        try:
            manifest = rospack.get_manifest(package)
            prefix = rospack.get_path(package)
        except Exception:  # noqa: BLE001 - a broken manifest of another package is skipped
            continue
        for export in manifest.exports:
            if export.tag == "gazebo_ros" and export.get("gazebo_model_path"):
                paths.append(export.get("gazebo_model_path").replace("${prefix}", prefix))
    return paths


class ModelPath:
    """The folders ``model://`` searches, in order. The ROS packages' exports are read only
    when a name is found nowhere else (they cost a scan of every manifest)."""

    def __init__(self, environ=os.environ,
                 ros_exports: Callable[[], List[str]] = _ros_exported_model_paths):
        self.environ = environ
        self._ros_exports = ros_exports
        self._exported: Optional[List[str]] = None

    def _groups(self) -> Iterable[Tuple[str, Sequence[str]]]:
        yield "GAZEBO_MODEL_PATH", [p for p in self.environ.get("GAZEBO_MODEL_PATH", "")
                                    .split(":") if p]
        home = self.environ.get("HOME")
        yield "~/.gazebo/models", ([USER_MODELS.replace("~", home, 1)] if home else [])
        yield "tutorial_turtlebot/models", [PACKAGE_MODELS]
        if self._exported is None:
            self._exported = self._ros_exports()
        yield "ROS packages' gazebo_model_path", self._exported

    def describe(self) -> str:
        """The searched folders for an error message: "GAZEBO_MODEL_PATH (a:b), ..."."""
        parts = []
        for label, folders in self._groups():
            if label == "GAZEBO_MODEL_PATH" or folders:
                parts.append("%s (%s)" % (label, ":".join(folders) or "unset"))
        return ", ".join(parts)

    def folders(self) -> Iterable[str]:
        """Every folder of the model path, in search order (the ROS exports read last, lazily)."""
        for _label, folders in self._groups():
            for folder in folders:
                yield os.path.expanduser(folder)

    def find(self, relative: str) -> Optional[str]:
        """The first existing ``folder/relative`` over the model path; None if there is none."""
        for folder in self.folders():
            candidate = os.path.join(folder, relative)
            if os.path.exists(candidate):
                return candidate
        return None

    def resource_folders(self) -> List[str]:
        """The folders of ``GAZEBO_RESOURCE_PATH`` (colon-separated), in order."""
        return [p for p in self.environ.get("GAZEBO_RESOURCE_PATH", "").split(":") if p]


_DEFAULT = ModelPath()


def split_uri(uri: str) -> Tuple[str, str]:
    """("model" | "package" | "file" | "", the rest) of a URI; "" for a bare path."""
    for scheme in ("model", "package", "file"):
        prefix = scheme + "://"
        if uri.startswith(prefix):
            return scheme, uri[len(prefix):]
    return "", uri


def resolve_uri(uri: str, base_dir: str, model_path: Optional[ModelPath] = None) -> str:
    """The absolute path of the existing file or folder ``uri`` names; relative paths are
    taken from ``base_dir``. AssetError (one line) if it cannot be found."""
    model_path = model_path or _DEFAULT
    uri = uri.strip()
    scheme, rest = split_uri(uri)
    if not rest:
        raise AssetError("empty URI %r" % uri)
    if "://" in rest and not scheme:
        if is_web_uri(uri):
            return _fuel(uri, model_path)
        raise AssetError("URI %r: only model://, package://, file://, Fuel URLs and paths are "
                         "read" % uri)
    if scheme == "model":
        found = model_path.find(rest.strip("/"))
        if found is None:
            tried = [os.path.join(f, rest.strip("/")) for f in model_path.folders()]
            note = _case_note(tried)
            searched = "model:// searched %s; %s" % (model_path.describe(), MODEL_DATABASE_HINT)
            raise AssetNotFound("%s not found: searched %s%s; %s"
                                % (uri, model_path.describe(), note, MODEL_DATABASE_HINT),
                                short="%s not found%s"
                                      % (uri, _case_note(tried, brief=True)),
                                searched=searched)
        return found
    if scheme == "package":
        package, _, inner = rest.partition("/")
        root = _package_path(package)
        if root is None:
            found = model_path.find(rest.strip("/"))
            if found is None:
                packages = os.environ.get("ROS_PACKAGE_PATH", "unset")
                raise AssetNotFound("%s: no ROS package %r on ROS_PACKAGE_PATH (%s) and no model "
                                    "folder of that name in %s"
                                    % (uri, package, packages, model_path.describe()),
                                    short="%s: no ROS package %r and no model folder of that name"
                                    % (uri, package),
                                    searched="package:// searched ROS_PACKAGE_PATH (%s), then %s"
                                    % (packages, model_path.describe()))
            return found
        path = os.path.join(root, inner)
    else:
        rest = os.path.expanduser(rest)
        if not os.path.isabs(rest):
            return _relative(uri, rest, base_dir, model_path)
        path = rest
    path = os.path.normpath(path)
    if not os.path.exists(path):
        raise AssetNotFound("%s not found (%s does not exist)%s"
                            % (uri, path, _case_note([path])))
    return path


def _fuel(uri: str, model_path: ModelPath) -> str:
    """The file (or model folder) of the Fuel URL ``uri`` (fuel_uri.fuel_file); AssetNotFound
    for an http(s) URI that is no Fuel URL, FuelNotCached for one found nowhere."""
    found, problem = fuel_file(uri, model_path.environ, model_path.find)
    if found is not None:
        return found
    if problem:
        raise AssetNotFound("URI %s: %s" % (uri, problem))
    searched = searched_line(model_path.environ, model_path.describe())
    raise FuelNotCached("%s not cached: %s" % (uri, searched), short="%s not cached" % uri,
                        searched=searched)


def _relative(uri: str, rest: str, base_dir: str, model_path: ModelPath) -> str:
    """The first existing ``folder/rest`` in Gazebo's order: the naming file's folder, the
    working directory, GAZEBO_RESOURCE_PATH, the model path. AssetNotFound naming them all."""
    first = [os.path.abspath(base_dir), os.getcwd()] + model_path.resource_folders()
    tried = []
    for folder in first + [None]:
        folders = [folder] if folder is not None else model_path.folders()
        for each in folders:
            candidate = os.path.normpath(os.path.join(each, rest))
            if os.path.exists(candidate):
                return candidate
            tried.append(candidate)
    resource = ":".join(model_path.resource_folders()) or "unset"
    note = _case_note(tried)
    raise AssetNotFound("%s not found: searched the folder of the file naming it (%s), the "
                        "working directory (%s), GAZEBO_RESOURCE_PATH (%s), %s%s"
                        % (uri, os.path.abspath(base_dir), os.getcwd(), resource,
                           model_path.describe(), note),
                        short="%s not found%s" % (uri, _case_note(tried, brief=True)),
                        searched="relative paths searched the naming file's folder, the working "
                                 "directory (%s), GAZEBO_RESOURCE_PATH (%s), %s"
                                 % (os.getcwd(), resource, model_path.describe()))


_ROSPACK = {}   # ROS_PACKAGE_PATH -> its rospkg.RosPack (each new one scans the whole path)


def _package_path(package: str) -> Optional[str]:
    try:
        import rospkg
    except ImportError:
        return None
    key = os.environ.get("ROS_PACKAGE_PATH", "")
    if key not in _ROSPACK:
        _ROSPACK[key] = rospkg.RosPack()
    try:
        return _ROSPACK[key].get_path(package)
    except rospkg.ResourceNotFound:
        return None


def _version(text: str) -> Tuple[int, ...]:
    """An SDF version "1.6" as (1, 6, 0); () for what is no version (Gazebo's SemanticVersion
    reads "-1", "1.x" or "" as 0.0.0, which is never better than another)."""
    parts = text.strip().split(".")
    # (a part of more than 9 digits is no version: 5,000 digits overran Python's int() limit)
    if not 1 <= len(parts) <= 3 or not all(p.isascii() and p.isdigit() and len(p) <= 9
                                           for p in parts):
        return ()
    version = tuple(int(p) for p in parts) + (0,) * (3 - len(parts))
    return version if version > (0, 0, 0) else ()


# What TinyXML 2.6 reads and expat does not, made into XML expat reads (line numbers kept):
_ENTITY = re.compile(r"&(?!(?:amp|lt|gt|quot|apos|#[0-9]+|#x[0-9a-fA-F]+);)")
_DECLARATION = re.compile(r"<\?.*?\?>|<!DOCTYPE(?:[^\[>]|\[[^\]]*\])*>", re.S)
_START_TAG = re.compile(r"<[A-Za-z_][^<>]*>")
_ATTRIBUTE = re.compile(r"(\s[^\s=<>/]+\s*=\s*)(\"[^\"]*\"|'[^']*'|[^\s\"'/>]+)")
_STRAY_LT = re.compile(r"<(?![A-Za-z_/!?])")
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")


def _quoted(match) -> str:
    """An attribute ``name=value`` with its value in quotes (it keeps them if it had some)."""
    value = match.group(2)
    return match.group(0) if value[0] in "\"'" else '%s"%s"' % (match.group(1), value)


def _as_tinyxml_reads_it(text: str) -> str:
    """``text`` with what TinyXML 2.6 tolerates written as XML: a ``&`` that starts no entity
    it knows is a literal ``&`` (TiXmlBase::GetEntity), an attribute value may go unquoted
    (TiXmlAttribute::Parse), a DOCTYPE is an unknown node it passes over, a ``<`` that starts
    no tag is text, control characters are text. Declarations go (they name an encoding that
    no longer applies); every newline stays, so line numbers stay."""
    text = _DECLARATION.sub(lambda m: "\n" * m.group(0).count("\n"), text)
    text = _CONTROL.sub(" ", text)
    text = _START_TAG.sub(lambda m: _ATTRIBUTE.sub(_quoted, m.group(0)), text)
    text = _STRAY_LT.sub("&lt;", text)
    return _ENTITY.sub("&amp;", text)


def read_model_config(data: bytes, source: str) -> xml_reader.Element:
    """The root element of a model.config's bytes, read as leniently as Gazebo 11 reads it
    (TinyXML 2.6); ModelLeftOut (one line) if even that cannot read it."""
    try:
        return xml_reader.parse(data, source, UserError)
    except UserError as strict:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            text = data.decode("latin-1")     # TinyXML reads bytes as they are
        try:
            return xml_reader.parse(_as_tinyxml_reads_it(text), source, UserError)
        except UserError:
            raise _left_out(source, "%s; Gazebo (TinyXML) cannot read it either: the model "
                                    "is left out" % str(strict)[len(source):]) from None


def _left_out(config: str, problem: str) -> "ModelLeftOut":
    """ModelLeftOut of ``problem`` (":line: ..." or ": ...") with a model.config: named by its
    whole path, and in ``short`` by its model folder's name alone (a warning line)."""
    short = os.path.join(os.path.basename(os.path.dirname(config)), os.path.basename(config))
    return ModelLeftOut(config + problem, short=short + problem)


def _config_file(model_dir: str) -> str:
    """The model folder's model.config, else its manifest.xml (which sdformat 9 still reads,
    with a warning); ModelLeftOut if it has neither."""
    for name in ("model.config", "manifest.xml"):
        path = os.path.join(model_dir, name)
        if os.path.lexists(path):
            return path
    raise ModelLeftOut("%s has no model.config: Gazebo leaves the model out" % model_dir,
                       short="%s has no model.config: Gazebo leaves the model out"
                             % os.path.basename(os.path.normpath(model_dir)))


def model_sdf_file(model_dir: str) -> str:
    """The SDF file of the model folder ``model_dir``, chosen from its model.config's ``<sdf
    version>`` entries as sdformat 9 chooses it (getBestSupportedModelVersion): the highest
    version up to 1.7, else the first entry. ModelLeftOut (the world loads without the model)
    for no model.config, one even TinyXML cannot read, or one naming no file; AssetError (the
    world is refused) for a model.config or SDF file that is no regular file or too big."""
    config = _config_file(model_dir)
    root = read_model_config(read_file(config, MAX_MODEL_CONFIG_BYTES, "model.config",
                                       AssetError), config)
    if root.tag != "model":
        raise _left_out(config, ":%d: the root element is <%s>, not <model>: Gazebo leaves "
                                "the model out" % (root.line, root.tag))
    entries = root.all("sdf")
    chosen, best = (entries[0] if entries else None), ()
    for node in entries:
        version = _version(node.attrib.get("version", ""))
        if version and version > best and version <= MAX_SDF_VERSION + (0,):
            chosen, best = node, version
    if chosen is None or not chosen.value:
        raise _left_out(config, ":%d: it names no <sdf version=\"1.x\">file</sdf>: Gazebo "
                                "leaves the model out" % root.line)
    path = os.path.join(model_dir, chosen.value)
    why = not_regular(path)
    if why is not None:
        raise AssetError("%s: its model.config names %s: %s" % (model_dir, chosen.value, why))
    return path
