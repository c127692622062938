"""What Gazebo 11's URDF conversion (sdformat 9's parser_urdf) makes of a URDF beyond its links
and joints, for urdf_file's reader: the model's ``<static>`` flag, and the visuals and collisions
whose mesh file cannot be found, left out with one warning line each (up to a few). No ROS, no
pybullet. A root link named ``world`` (``WORLD_LINK``) is the world itself: the model is joined
to it (urdf_to_sdf writes those joints).
"""
from typing import List, Tuple

from ..sdf.sdf_elements import MAX_WARNING_CHARS, one_line
from ..xml_reader import Element, element

WORLD_LINK = "world"        # a root link of this name is the world, as in parser_urdf
MAX_MISSING_LINES = 3       # missing mesh files named one line each; the rest in one more line


def read_static(root: Element, source: str) -> Tuple[bool, List[str]]:
    """(whether the model is static, warning lines) of a URDF ``<robot>``. As parser_urdf: each
    ``<gazebo>`` block without a ``reference`` (or with an empty one) sets the model's static
    flag, true for a ``<static>`` of "true", "yes" or "1" (any case; its ``value`` attribute,
    else its text), false otherwise, a block without ``<static>`` too; the last block decides.
    One warning when a later block turns a true flag false again (Gazebo warns then too)."""
    static, since = False, None
    warnings: List[str] = []
    for block in root.findall("gazebo"):
        if block.get("reference", "").strip():
            continue
        value = False
        for flag in block.findall("static"):
            text = flag.get("value", flag.text or "").strip()
            value = text.lower() in ("true", "yes") or text == "1"
        if static and not value:
            warnings.append(one_line(source, block.line, "this <gazebo> block makes the model "
                                     "not static, undoing <static> of line %d, as Gazebo does "
                                     "(the last <gazebo> without a reference decides)" % since))
        static = value
        since = block.line if value else None
    return static, warnings


class MissingMeshes:
    """The visuals and collisions left out of one URDF because their mesh file is found
    nowhere (Gazebo loads the link without them): ``left_out`` in reading order, and the
    warnings, one line per missing file up to MAX_MISSING_LINES, the folders searched once,
    then one line for the rest."""

    def __init__(self, source: str):
        self.source = source
        self.left_out: List[Element] = []
        self._files: List[str] = []
        self._lines: List[str] = []

    def add(self, holder: Element, mesh: Element, owner: str, uri: str, err) -> None:
        """``holder`` (a <visual> or <collision> of ``owner``, "link 'a'") is left out: its
        ``mesh`` names ``uri``, which asset_uri could not find (``err``: its AssetNotFound)."""
        self.left_out.append(holder)
        if uri in self._files:
            return
        self._files.append(uri)
        if len(self._files) <= MAX_MISSING_LINES:
            self._lines.append(one_line(self.source, mesh.line, "%s <%s> left out: %s" % (
                owner, holder.tag, getattr(err, "short", str(err)))))
            searched = _cut(getattr(err, "searched", ""))
            if searched and searched not in self._lines:
                self._lines.append(searched)

    def warnings(self) -> List[str]:
        """The warning lines, each at most MAX_WARNING_CHARS characters."""
        rest = self._files[MAX_MISSING_LINES:]
        if not rest:
            return list(self._lines)
        return self._lines + [_cut(
            "%s: %d more mesh files not found, their visuals and collisions left out too: %s"
            % (self.source, len(rest), ", ".join(rest)))]

    def trimmed(self, root: Element) -> Element:
        """``root`` itself if nothing was left out, else a copy of it without what was (lines
        kept): the ``<robot>`` whoever writes the URDF out again uses."""
        if not self.left_out:
            return root
        return _without(root, {id(e) for e in self.left_out})


def _cut(line: str) -> str:
    """``line`` in at most MAX_WARNING_CHARS characters."""
    return line if len(line) <= MAX_WARNING_CHARS else line[:MAX_WARNING_CHARS - 3] + "..."


def _without(node: Element, dropped: set) -> Element:
    """A copy of ``node`` without the elements whose id() is in ``dropped``, lines kept."""
    copy = element(node.tag, node.attrib, node.line,
                   [_without(child, dropped) for child in node if id(child) not in dropped])
    copy.text, copy.tail = node.text, node.tail
    return copy
