"""OGRE material scripts of a model's own (``.material`` files), read as Gazebo 11 reads them for
a visual's ``<material><script>``: the colour and the texture image of a named material.

No ROS and no pybullet here. A ``<script>``'s ``<uri>``s name folders (or files); every
``.material`` file of a folder is read, in name order, and the first definition of a name
wins. Of ``material NAME { technique { pass { ... } } }`` only the first technique's first pass
is used: its ``diffuse r g b [a]`` (else ``ambient``) colour and the image of its first
``texture_unit``'s ``texture FILE``. The image is looked for in each ``<uri>`` folder, and in the
``textures`` folder beside a ``scripts`` folder (as Gazebo adds them to its resource paths);
it is used if it is a PNG or JPEG file that texture_images.image_problem takes. ``material A : B``
takes from B what A's pass does not set. Shaders, further passes and texture units, scrolling,
blending and the like are left out without a word.

The OGRE syntax read: words and ``"quoted names"``, one property a line, an object a line of
words followed by ``{ ... }`` (on that line or the next), ``//`` and ``/* */`` comments.
Every file is a regular file of at most MAX_SCRIPT_BYTES (file_read). A file that cannot be read
or is malformed, a colour that is not numbers, a texture that cannot be used: one line each
(file, line, what is wrong), and the material drawn as far as it can be, else not at all
(the caller's grey). Nothing here raises for a bad script.
"""
import math
import os
import re
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

from ....errors import UserError
from ..file_read import MAX_MESH_SIDE_FILE_BYTES, MAX_XML_FILE_BYTES, not_regular, read_file
from ..meshes.texture_images import image_problem

Rgba = Tuple[float, float, float, float]
WHITE: Rgba = (1.0, 1.0, 1.0, 1.0)
SUFFIX = ".material"
MAX_SCRIPT_BYTES = MAX_XML_FILE_BYTES   # one .material file: text, held as a world file is
MAX_SCRIPT_FILES = 256     # .material files read of one folder (in name order): the rest left out
MAX_NESTING = 32           # braces nested deeper than this: a malformed file
MAX_INHERITANCE = 16       # ``material A : B`` chains followed at most this far


@dataclass(frozen=True)
class ScriptMaterial:
    """What a named material of a script draws: a colour (0..1) and an image, each or both."""

    name: str
    rgba: Optional[Rgba]     # its pass's diffuse, else ambient, else WHITE with a texture,
    #                          else None
    texture: Optional[str]   # absolute path of its usable PNG or JPEG image; None if none


@dataclass(frozen=True)
class _Definition:
    """One ``material`` of a file, as written (nothing looked up yet)."""

    name: str
    parent: Optional[str]           # B of ``material A : B``
    diffuse: Optional[Rgba]
    ambient: Optional[Rgba]
    texture: Optional[str]          # the file name as written
    path: str                       # the .material file
    line: int                       # of the ``texture`` property (else of the material)


class _Node:
    """A property (``children`` None) or an object of a script: its words and its line."""

    __slots__ = ("words", "line", "children")

    def __init__(self, words: Tuple[str, ...], line: int, children: Optional[list]):
        self.words, self.line, self.children = words, line, children


class _Malformed(Exception):
    """A script that cannot be parsed: (line, what is wrong)."""


_TOKEN = re.compile(r"""
    (?P<nl>\n)
  | [ \t\r\f\v]+
  | //[^\n]*
  | (?P<block>/\*.*?\*/)
  | "(?P<quoted>[^"\n]*)"
  | (?P<brace>[{}])
  | (?P<word>(?:[^\s{}"/]|/(?![/*]))+)
  | (?P<bad>.)
""", re.VERBOSE | re.DOTALL)


def _tokens(text: str) -> List[Tuple[str, str, int]]:
    """(kind, text, line) of each token: kind "nl", "{", "}" or "w" (a word or quoted name)."""
    out, line = [], 1
    for m in _TOKEN.finditer(text):
        if m.group("nl"):
            out.append(("nl", "", line))
            line += 1
        elif m.group("block"):
            line += m.group("block").count("\n")
        elif m.group("quoted") is not None:
            out.append(("w", m.group("quoted"), line))
        elif m.group("brace"):
            out.append((m.group("brace"), m.group("brace"), line))
        elif m.group("word"):
            out.append(("w", m.group("word"), line))
        elif m.group("bad"):
            what = "a quoted name not closed on its line" if m.group("bad") == '"' \
                else "a /* comment never closed"
            raise _Malformed(line, what)
    return out


def parse_script(text: str) -> List[_Node]:
    """The top-level objects and properties of a script's text; _Malformed if braces do not
    pair up, nest deeper than MAX_NESTING, or a quote or comment is not closed."""
    root: List[_Node] = []
    stack: List[Tuple[list, int]] = [(root, 0)]     # (children, line of its "{")
    words: List[str] = []
    words_line = 0
    ended = False                                    # the words' line has ended

    def flush():
        if words:
            stack[-1][0].append(_Node(tuple(words), words_line, None))
            del words[:]

    for kind, value, line in _tokens(text):
        if kind == "nl":
            ended = bool(words)
        elif kind == "w":
            if ended:
                flush()
                ended = False
            if not words:
                words_line = line
            words.append(value)
        elif kind == "{":
            if not words:
                raise _Malformed(line, "a '{' without a name before it")
            if len(stack) > MAX_NESTING:
                raise _Malformed(line, "braces nested more than %d deep" % MAX_NESTING)
            node = _Node(tuple(words), words_line, [])
            stack[-1][0].append(node)
            stack.append((node.children, line))
            del words[:]
            ended = False
        else:
            flush()
            ended = False
            if len(stack) == 1:
                raise _Malformed(line, "a '}' without its '{'")
            stack.pop()
    flush()
    if len(stack) > 1:
        raise _Malformed(stack[-1][1], "a '{' never closed")
    return root


def _objects(node: _Node, keyword: str) -> List[_Node]:
    return [c for c in node.children if c.children is not None and c.words[0] == keyword]


def _property(node: _Node, keyword: str) -> Optional[_Node]:
    return next((c for c in node.children if c.children is None and c.words[0] == keyword), None)


def _colour(node: Optional[_Node], path: str, problems: List[str]) -> Optional[Rgba]:
    """``diffuse r g b [a]`` (or ``ambient``) as an Rgba clamped to 0..1; None if absent, or
    ``vertexcolour``; None and a problem if it is not 3 or 4 numbers."""
    if node is None or node.words[1:2] == ("vertexcolour",):
        return None
    values = node.words[1:]
    try:
        numbers = [float(v) for v in values]
    except ValueError:
        numbers = []
    if len(numbers) not in (3, 4) or not all(math.isfinite(v) for v in numbers):
        problems.append("%s:%d: %s needs 3 or 4 numbers, got %r; left out"
                        % (path, node.line, node.words[0], " ".join(values)))
        return None
    numbers += [1.0] * (4 - len(numbers))
    return tuple(min(max(v, 0.0), 1.0) for v in numbers)


def definitions(nodes: List[_Node], path: str, problems: List[str]) -> Dict[str, _Definition]:
    """The materials of a parsed script by name, the first of a name kept; a colour that
    cannot be read is one line in ``problems``."""
    out: Dict[str, _Definition] = {}
    for node in nodes:
        if node.children is None or node.words[0] != "material" or len(node.words) < 2:
            continue
        words = node.words
        parent = words[3] if len(words) >= 4 and words[2] == ":" else None
        diffuse = ambient = texture = None
        line = node.line
        techniques = _objects(node, "technique")
        passes = _objects(techniques[0], "pass") if techniques else []
        if passes:
            first = passes[0]
            diffuse = _colour(_property(first, "diffuse"), path, problems)
            ambient = _colour(_property(first, "ambient"), path, problems)
            for unit in _objects(first, "texture_unit"):
                found = _property(unit, "texture")
                if found is not None and len(found.words) >= 2:
                    texture, line = found.words[1], found.line
                    break
        out.setdefault(words[1], _Definition(words[1], parent, diffuse, ambient, texture,
                                             path, line))
    return out


class MaterialScripts:
    """The material scripts read during one world load: each file and folder read once."""

    def __init__(self):
        self._files: Dict[str, Tuple[Dict[str, _Definition], List[str]]] = {}
        self._folders: Dict[str, Tuple[List[str], List[str]]] = {}
        self._textures: Dict[str, Optional[str]] = {}     # image path -> why unusable, or None

    def material(self, name: str, places: Sequence[str]
                 ) -> Tuple[Optional[ScriptMaterial], List[str]]:
        """(the material ``name`` as the scripts of ``places`` define it, or None if none
        does; the one-line problems met). ``places``: a ``<script>``'s ``<uri>``s as absolute
        folders or files."""
        problems: List[str] = []
        files: List[str] = []
        for place in places:
            if os.path.isdir(place):
                listed, trouble = self._folder(place)
                files.extend(listed)
                problems.extend(trouble)
            elif place.endswith(SUFFIX):
                files.append(place)
        found = self._definition(name, files, problems)
        if found is None:
            if files and not problems:
                problems.append("material %s is defined in none of %s; drawn grey"
                                % (name, ", ".join(files)))
            return None, problems
        chain = [found]
        while chain[-1].parent and len(chain) <= MAX_INHERITANCE:
            parent = self._definition(chain[-1].parent, files, problems)
            if parent is None or parent in chain:
                break
            chain.append(parent)
        diffuse = next((d.diffuse for d in chain if d.diffuse is not None), None)
        ambient = next((d.ambient for d in chain if d.ambient is not None), None)
        with_texture = next((d for d in chain if d.texture is not None), None)
        texture = None
        if with_texture is not None:
            texture = self._texture(with_texture, places, problems)
        rgba = diffuse or ambient or (WHITE if texture is not None else None)
        return ScriptMaterial(name, rgba, texture), problems

    def _folder(self, folder: str) -> Tuple[List[str], List[str]]:
        """(the .material files of ``folder`` in name order, problems), listed once."""
        if folder not in self._folders:
            problems: List[str] = []
            try:
                names = sorted(n for n in os.listdir(folder) if n.endswith(SUFFIX))
            except OSError as err:
                names = []
                problems.append("%s: cannot list material scripts: %s"
                                % (folder, err.strerror or err))
            if len(names) > MAX_SCRIPT_FILES:
                problems.append("%s: more than %d material scripts; those after %s left out"
                                % (folder, MAX_SCRIPT_FILES, names[MAX_SCRIPT_FILES - 1]))
                names = names[:MAX_SCRIPT_FILES]
            self._folders[folder] = ([os.path.join(folder, n) for n in names], problems)
        return self._folders[folder]

    def _definition(self, name: str, files: Sequence[str],
                    problems: List[str]) -> Optional[_Definition]:
        """The first definition of ``name`` in ``files``; their problems into ``problems``."""
        for path in files:
            definitions_of, trouble = self._file(path)
            for problem in trouble:
                if problem not in problems:
                    problems.append(problem)
            if name in definitions_of:
                return definitions_of[name]
        return None

    def _file(self, path: str) -> Tuple[Dict[str, _Definition], List[str]]:
        """(the materials of the script ``path``, its problems), read and parsed once."""
        if path not in self._files:
            problems: List[str] = []
            found: Dict[str, _Definition] = {}
            try:
                data = read_file(path, MAX_SCRIPT_BYTES, "a material script")
                found = definitions(parse_script(data.decode("utf-8", "replace")), path,
                                    problems)
            except UserError as err:
                problems.append("%s; its materials are drawn grey" % err)
            except _Malformed as err:
                line, what = err.args
                problems.append("%s:%d: malformed material script (%s); its materials are "
                                "drawn grey" % (path, line, what))
            self._files[path] = (found, problems)
        return self._files[path]

    def _texture(self, definition: _Definition, places: Sequence[str],
                 problems: List[str]) -> Optional[str]:
        """The usable image a material's texture names, looked for in each place's folder and
        the ``textures`` folder beside a ``scripts`` folder; None and a problem if none."""
        written = definition.texture
        folders: List[str] = []
        for place in list(places) + [os.path.dirname(definition.path)]:
            folder = place if os.path.isdir(place) else os.path.dirname(place)
            folders.append(folder)
            if os.path.basename(os.path.normpath(folder)) == "scripts":
                folders.append(os.path.join(os.path.dirname(os.path.normpath(folder)),
                                            "textures"))
        candidates: List[str] = []
        for folder in folders:
            for name in (written, os.path.basename(written.replace("\\", "/"))):
                candidate = os.path.abspath(os.path.join(folder, name))
                if candidate not in candidates:
                    candidates.append(candidate)
        found = next((c for c in candidates if os.path.lexists(c)), None)
        where = "material %s (%s:%d)" % (definition.name, definition.path, definition.line)
        if found is None:
            looked = ", ".join(dict.fromkeys(os.path.dirname(c) for c in candidates))
            problems.append("texture %s of %s found nowhere; looked in %s; drawn in its colour"
                            % (written, where, looked))
            return None
        why = self._image_problem(found)
        if why is not None:
            problems.append("texture %s of %s not drawn (%s); drawn in its colour"
                            % (written, where, why))
            return None
        return found

    def _image_problem(self, path: str) -> Optional[str]:
        """Why the file ``path`` is no texture drawn here (one line), or None; checked once."""
        if path not in self._textures:
            why = not_regular(path)
            if why is None:
                try:
                    why = image_problem(read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a texture"))
                except UserError as err:
                    why = str(err)
            else:
                why = "%s: %s" % (path, why)
            self._textures[path] = why
        return self._textures[path]
