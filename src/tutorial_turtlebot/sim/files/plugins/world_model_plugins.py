"""The model plugins (those of ``table`` that run on world models) of a world file's model, or
of a spawned SDF model, read with the world loader's file and warnings: a wrong value is a
WorldError of one line, a plugin Gazebo would not run (no <bodyName>, an unknown link or
joint) one warning line naming its file and line. Which ``<plugin>`` elements get here is the
loader's (sdf_elements: the "plugin" row of "model"; any other plugin is one warning per
world). No ROS, no pybullet.
"""
from typing import List, Sequence, Tuple

from ....errors import WorldError
from .. import limits, xml_reader
from ..sdf.sdf_elements import one_line
from .sensor_reader import SensorReader
from .table import read_model_plugin

WITHOUT = "the world runs without it"


class _ModelPluginReader(SensorReader):
    host = "world"

    def __init__(self, path: str, warnings: List[str]):
        super().__init__(path, WorldError, WITHOUT)
        self.warnings = warnings

    def warn(self, message: str, elem=None) -> None:
        line = one_line(self.source, elem.line if elem is not None else 0, message)
        if line not in self.warnings:
            self.warnings.append(line)

    def wheel_joint(self, plugin, tag: str, default: str) -> str:
        """The joint a drive's <tag> names (one of the model's: the drive module checked it
        with model_plugin_values.joints_found)."""
        return self.text(plugin, tag, default)


def read_model_plugins(path: str, warnings: List[str], nodes: Sequence, model: str,
                       links: Sequence[str], joints: Sequence[str]) -> List[object]:
    """The data of the model plugins ``nodes`` (<plugin> elements, read from ``path``) of the
    top-level model ``model``, whose links (names below the model: "link", "inner::link") and
    joints are ``links`` and ``joints``; warnings go to ``warnings``."""
    reader = _ModelPluginReader(path, warnings)
    out = []
    for node in nodes:
        for elem in node.iter():
            for key, value in elem.attrib.items():
                problem = limits.name_problem(key, value)
                if problem:
                    reader.fail_bare(elem, "<%s>: %s" % (elem.tag, problem))
        plugin = read_model_plugin(reader, node, model, links, joints)
        if plugin is not None:
            out.append(plugin)
    return out


class ModelPluginReading:
    """The model plugins read so far in one world document and the documents it includes (one
    object shared by their loaders): ``nodes``, the <plugin>s that run here of the top-level
    model being read (nested and included parts adding theirs), then each model's data."""

    def __init__(self):
        self.nodes: List = []
        self._found: List[Tuple[object, List[object]]] = []   # (Model, its plugins' data)

    def kept(self, node, skipped: bool) -> None:
        """Keep the model's child ``node`` if it is a <plugin> the loader did not skip."""
        if node.tag == "plugin" and not skipped:
            self.nodes.append(node)

    def read(self, loader, model):
        """Read the kept nodes of ``model`` (a world_types.Model just read by ``loader``, a
        world_sdf loader: its file and warnings); ``model``."""
        if self.nodes:
            self._found.append((model, read_model_plugins(
                loader.path, loader.warnings, self.nodes, model.name,
                [link.scoped.split("::", 1)[1] for link in model.links], model.joints)))
        self.nodes = []
        return model

    def of(self, models: Sequence[object]) -> Tuple[object, ...]:
        """The plugins, in file order, of ``models`` (the world's Models): a model left out (a
        second of one name) takes its plugins along."""
        return tuple(p for m, found in self._found if any(m is k for k in models)
                     for p in found)


def with_plugins(model, plugins: Sequence):
    """The <model> element ``model`` with the <plugin>s an <include> adds (sdformat 9)."""
    if not plugins:
        return model
    return xml_reader.element(model.tag, dict(model.attrib), model.line,
                              list(model.children) + list(plugins))
