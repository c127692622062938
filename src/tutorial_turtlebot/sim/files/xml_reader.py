"""The one line-numbered XML reader of the simulator: URDF, SDF, robot plugins, spawn requests.

``parse`` turns XML text into ``Element``s (xml.etree elements that know their ``line``);
``XmlReader`` reads typed values out of them. Every problem is one line of one form:

    <source>:<line>: <element>: <what is wrong>

where <source> is a file's path or what names a text (e.g. "model_xml"), and <element> says
which element is at fault ("<origin>", or a reader's own naming such as "link 'base'").
A DOCTYPE is refused (entities are never expanded), and so is nesting deeper than
``MAX_DEPTH`` elements. No ROS, no pybullet.
"""
import math
import re
from typing import Callable, List, NoReturn, Optional, Sequence, Tuple, Type, Union
from xml.etree import ElementTree
from xml.parsers import expat

from ...errors import UserError
from .file_read import MAX_XML_FILE_BYTES, read_file

MAX_DEPTH = 64          # elements nested deeper than this are refused (no real model nests so)


class Element(ElementTree.Element):
    """An xml.etree element with the ``line`` (from 1) where its start tag stands."""

    line = 0

    def child(self, tag: str) -> Optional["Element"]:
        """The first child ``<tag>``; None if there is none."""
        return self.find(tag)

    def all(self, tag: str) -> List["Element"]:
        """Every child ``<tag>``, in document order."""
        return self.findall(tag)

    @property
    def children(self) -> List["Element"]:
        return list(self)

    @property
    def value(self) -> str:
        """The element's own text, without surrounding white space ("" if it has none)."""
        return (self.text or "").strip()


def element(tag: str, attrib: dict, line: int, children: Sequence[Element] = ()) -> Element:
    """A new Element (e.g. a model rebuilt with an <include>'s overrides) said to stand at
    ``line``."""
    node = Element(tag, dict(attrib))
    node.line = line
    node.extend(children)
    return node


def located(source: str, line, where: str, problem: str) -> str:
    """The one error line: ``<source>:<line>: <where>: <problem>`` (no ``<where>`` if empty)."""
    return "%s:%s: %s" % (source, line, "%s: %s" % (where, problem) if where else problem)


class _Refused(Exception):
    pass


def parse(data: Union[str, bytes], source: str, error: Type[UserError] = UserError,
          max_depth: int = MAX_DEPTH) -> Element:
    """The root Element of the XML text ``data``; ``error`` (one line naming ``source`` and the
    line) for malformed XML, a DOCTYPE, or nesting deeper than ``max_depth`` elements."""
    if not isinstance(data, (str, bytes)):
        raise error("%s: the XML must be text, not %s" % (source, type(data).__name__))
    builder = ElementTree.TreeBuilder(element_factory=Element)
    parser = expat.ParserCreate()
    depth = [0]

    def start(tag, attrib):
        if depth[0] >= max_depth:
            raise _Refused(located(source, parser.CurrentLineNumber, "",
                                   "elements nested more than %d deep" % max_depth))
        depth[0] += 1
        builder.start(tag, attrib).line = parser.CurrentLineNumber

    def end(tag):
        depth[0] -= 1
        builder.end(tag)

    def doctype(*_args):
        raise _Refused(located(source, parser.CurrentLineNumber, "",
                               "a DOCTYPE (entity definitions) is not supported"))

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = builder.data
    parser.StartDoctypeDeclHandler = doctype
    data = _declaration_first(data)
    try:
        parser.Parse(data, True)
    except _Refused as err:
        raise error(str(err)) from None
    except expat.ExpatError as err:
        raise error(located(source, err.lineno, "", "malformed XML: %s (column %d)"
                            % (expat.ErrorString(err.code), err.offset + 1))) from None
    return builder.close()


_LATE_DECLARATION = {str: re.compile(r"\A((?:\s|<!--.*?-->)+)(<\?xml[^>\n]*\?>)", re.S),
                     bytes: re.compile(rb"\A((?:\s|<!--.*?-->)+)(<\?xml[^>\n]*\?>)", re.S)}


def _declaration_first(data: Union[str, bytes]) -> Union[str, bytes]:
    """``data`` with an XML declaration that white space or comments precede put first (they
    follow it: every line keeps its number). Gazebo's TinyXML reads such files (published worlds
    begin with blank lines, or a comment); expat refuses them."""
    return _LATE_DECLARATION[type(data)].sub(lambda m: m.group(2) + m.group(1), data, count=1)


def parse_file(path: str, what: str, error: Type[UserError] = UserError) -> Element:
    """The root Element of the XML file at ``path``; ``error`` for a file that cannot be read
    ("<path>: cannot read <what>: <why>": also one that is not a regular file or is larger
    than file_read.MAX_XML_FILE_BYTES) or any problem of ``parse``."""
    return parse(read_file(path, MAX_XML_FILE_BYTES, what, error), path, error)


def numbers(text: str, count: int, finite: bool = True) -> Optional[Tuple[float, ...]]:
    """``count`` numbers written in ``text`` (white space between); None if it is not that.
    ``finite`` False lets NaN and inf through (to a range check of limits, which names it)."""
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        return None
    if len(values) != count or (finite and not all(map(math.isfinite, values))):
        return None
    return values


def boolean(text: str) -> bool:
    """sdformat's bool: true/false/1/0, any case; ValueError for anything else."""
    word = text.strip().lower()
    if word in ("true", "1"):
        return True
    if word in ("false", "0"):
        return False
    raise ValueError(text)


def _count(count: int) -> str:
    return "a number" if count == 1 else "%d numbers" % count


Owner = Union[None, str, Element]


class XmlReader:
    """Typed values of the elements of one document, each fault raised as ``error`` in the
    one line form. A reader of a kind names elements its way by overriding ``describe``."""

    def __init__(self, source: str, error: Type[UserError] = UserError):
        self.source = source
        self.error = error

    def parse(self, data) -> Element:
        """``parse`` of ``data``, named ``self.source``."""
        return parse(data, self.source, self.error)

    # --- messages ----------------------------------------------------------------------------

    def describe(self, elem: Element) -> str:
        """How messages call ``elem``: "<tag>"."""
        return "<%s>" % elem.tag

    def where(self, elem: Element, owner: Owner = None) -> str:
        """``elem`` as messages name it, after its ``owner`` (a description, or an element
        around it) when there is one."""
        own = self.describe(elem)
        if owner is None or owner is elem:
            return own
        outer = owner if isinstance(owner, str) else self.describe(owner)
        return own if outer == own else "%s %s" % (outer, own)

    def fail(self, elem: Element, problem: str, owner: Owner = None) -> NoReturn:
        """Raise the one-line error about ``elem`` (inside ``owner``)."""
        raise self.error(located(self.source, elem.line, self.where(elem, owner), problem))

    def fail_bare(self, elem: Element, problem: str) -> NoReturn:
        """Raise the one-line error at ``elem``'s line whose ``problem`` names what is at
        fault itself."""
        raise self.error(located(self.source, elem.line, "", problem))

    # --- children and attributes -------------------------------------------------------------

    def child(self, parent: Element, tag: str, owner: Owner = None) -> Element:
        """The required child ``<tag>`` of ``parent``."""
        found = parent.find(tag)
        if found is None:
            self.fail(parent, "missing <%s>" % tag, owner)
        return found

    def attr(self, elem: Element, key: str, owner: Owner = None) -> str:
        """The required, non-blank attribute ``key`` of ``elem``, stripped."""
        value = elem.get(key, "").strip()
        if not value:
            self.fail(elem, "missing attribute %r" % key, owner)
        return value

    def attr_floats(self, elem: Element, key: str, count: int, owner: Owner = None,
                    finite: bool = True) -> Tuple[float, ...]:
        """The ``count`` numbers of the required attribute ``key``."""
        text = self.attr(elem, key, owner)
        values = numbers(text, count, finite)
        if values is None:
            self.fail(elem, "%s=%r is not %s" % (key, text, _count(count)), owner)
        return values

    # --- element text ------------------------------------------------------------------------

    def floats(self, elem: Element, count: int, owner: Owner = None,
               finite: bool = True) -> Tuple[float, ...]:
        """The ``count`` numbers of ``elem``'s text."""
        values = numbers(elem.value, count, finite)
        if values is None:
            self.fail(elem, "must be %s, got %r" % (_count(count), elem.value), owner)
        return values

    def convert(self, parent: Optional[Element], tag: str, default, convert: Callable,
                what: str, owner: Owner = None):
        """``convert`` of the text of ``parent``'s optional child ``<tag>`` (ValueError: it is
        not ``what``); ``default`` when there is no such child (or no ``parent``)."""
        elem = parent.find(tag) if parent is not None else None
        if elem is None:
            return default
        try:
            return convert(elem.value)
        except ValueError:
            self.fail(elem, "must be %s, got %r" % (what, elem.value), owner)

    def number(self, parent: Optional[Element], tag: str, default: float,
               owner: Owner = None) -> float:
        """The finite number of the optional child ``<tag>``."""
        return self.convert(parent, tag, default, _finite, "a number", owner)

    def integer(self, parent: Optional[Element], tag: str, default: int,
                owner: Owner = None) -> int:
        """The positive integer of the optional child ``<tag>``."""
        return self.convert(parent, tag, default, _positive_integer, "a positive integer", owner)

    def flag(self, parent: Optional[Element], tag: str, default: bool,
             owner: Owner = None) -> bool:
        """The bool (true/false/1/0) of the optional child ``<tag>``."""
        return self.convert(parent, tag, default, boolean, "true or false", owner)

    def xyz_rpy(self, parent: Optional[Element], tag: str, default,
                owner: Owner = None) -> Tuple[float, ...]:
        """The pose text "x y z roll pitch yaw" (m, rad) of the optional child ``<tag>``."""
        return self.convert(parent, tag, default, _six_numbers,
                            "six numbers (x y z roll pitch yaw)", owner)


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value


def _positive_integer(text: str) -> int:
    value = int(text)
    if value <= 0:
        raise ValueError(text)
    return value


def _six_numbers(text: str) -> Tuple[float, ...]:
    values = numbers(text, 6)
    if values is None:
        raise ValueError(text)
    return values
