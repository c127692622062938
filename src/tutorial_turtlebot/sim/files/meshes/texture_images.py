"""Texture images of meshes: where a mesh's image is found, whether it can be drawn, its size and
digest, and copies of it halved in size (the texture budget, rendering.plan_textures). No ROS
and no pybullet here.

An image named by a mesh is looked for as written (relative: beside the mesh), then by its last
part beside the mesh and in ``../materials/textures`` (a Gazebo model folder's place for them).
It is used only if it is a regular PNG or JPEG file (what pybullet's image loader, stb_image,
reads) of at most MAX_MESH_SIDE_FILE_BYTES and MAX_IMAGE_SIDE px a side. Otherwise its part keeps
its colour and ``texture_line`` says why in one line. An image over MAX_TEXTURE_SIDE px a side is
drawn from a copy halved until it fits (``fit_halvings``): ``TextureInfo`` gives its size as
drawn, and obj_writer.texture_copy halves it so.
"""
import hashlib
import io
import os
import struct
import urllib.parse
from dataclasses import dataclass
from typing import Dict, Optional, Tuple

from ..file_read import MAX_MESH_SIDE_FILE_BYTES
from .mesh_side_files import read_file
from .mesh_types import MeshError

MAX_TEXTURE_SIDE = 4096      # px: a larger texture image is drawn from a copy halved to fit
MAX_IMAGE_SIDE = 8192        # px: a larger one is not read (its part keeps its colour); Pillow
#                              holds 256 MB to halve an 8192 x 8192 RGBA image
MIN_HALVED_SIDE = 8          # px: halving stops at this side (a texture is never dropped)


def texture_line(mesh_path: str, name: str, why: str) -> str:
    """The one line of a texture that is not drawn: the mesh file by its name (the warning
    that carries it names the file and line of the ``<uri>`` that names the mesh)."""
    return "%s: texture %s not drawn (%s); drawn in its colour" % (
        os.path.basename(mesh_path), " ".join(name.split()), why)


def find_texture(mesh_path: str, name: str) -> Tuple[Optional[str], Optional[str]]:
    """(absolute path, None) of the usable image file the mesh ``mesh_path`` names ``name`` (a
    path or ``file://`` URI, %-escapes allowed, Windows' backslashes too), or (None, the one
    line why not)."""
    written = urllib.parse.unquote(name.strip())
    if written.startswith("file://"):
        written = written[len("file://"):]
    if not written:
        return None, texture_line(mesh_path, repr(name), "no file name")
    base = os.path.basename(written.replace("\\", "/"))
    folder = os.path.dirname(mesh_path)
    candidates = [os.path.join(folder, written), os.path.join(folder, base),
                  os.path.join(folder, os.pardir, "materials", "textures", base)]
    found = next((os.path.abspath(c) for c in candidates if os.path.lexists(c)), None)
    if found is None:
        return None, texture_line(mesh_path, written, "found nowhere: not as written, not "
                                  "beside the mesh, not in ../materials/textures")
    try:
        data = read_file(found, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
    except MeshError as err:
        return None, texture_line(mesh_path, written, str(err))
    why = image_problem(data)
    if why is not None:
        return None, texture_line(mesh_path, written, "%s: %s" % (found, why))
    return found, None


@dataclass(frozen=True)
class TextureInfo:
    """A usable texture file as it is now."""

    digest: str   # sha256 (hex) of its bytes
    width: int    # px, as drawn (after fit_halvings)
    height: int   # px, as drawn

    @property
    def pixels(self) -> int:
        return self.width * self.height


_infos: Dict[tuple, Optional[TextureInfo]] = {}   # (real path, mtime, size) -> info


def texture_info(path: str) -> Optional[TextureInfo]:
    """Digest and size of the texture file ``path``; None if it is no usable texture now."""
    try:
        stat = os.stat(path)
    except OSError:
        return None
    key = (os.path.realpath(path), stat.st_mtime_ns, stat.st_size)
    if key not in _infos:
        try:
            data = read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
        except MeshError:
            return None
        size = image_size(data) if image_problem(data) is None else None
        if len(_infos) > 4096:
            _infos.clear()
        if size:
            size = halved_size(size[0], size[1], fit_halvings(*size))
        _infos[key] = (TextureInfo(hashlib.sha256(data).hexdigest(), *size) if size else None)
    return _infos[key]


def image_size(data: bytes) -> Optional[Tuple[int, int]]:
    """(width, height) px of PNG or JPEG bytes; None if not found."""
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        if len(data) >= 24 and data[12:16] == b"IHDR":
            return struct.unpack(">II", data[16:24])
        return None
    if data[:3] == b"\xff\xd8\xff":
        return jpeg_size(data)
    return None


def image_problem(data: bytes) -> Optional[str]:
    """Why the bytes of an image file are no texture drawn here: not PNG or baseline/progressive
    JPEG (what pybullet's stb_image reads), or wider or taller than MAX_IMAGE_SIDE px; None if
    they are one."""
    if data[:8] != b"\x89PNG\r\n\x1a\n" and data[:3] != b"\xff\xd8\xff":
        return "neither a PNG nor a JPEG file"
    size = image_size(data)
    if size is None and data[:1] == b"\xff":
        return "a JPEG file without a frame size this reader takes"
    if size is None or 0 in size:
        return "a broken image file"
    if max(size) > MAX_IMAGE_SIDE:
        return "%d x %d px, more than %d px a side" % (size[0], size[1], MAX_IMAGE_SIDE)
    return None


def fit_halvings(width: int, height: int) -> int:
    """How many times an image of ``width`` x ``height`` px is halved to be drawn: until no
    side is over MAX_TEXTURE_SIDE px (0 for most)."""
    halvings = 0
    while max(halved_size(width, height, halvings)) > MAX_TEXTURE_SIDE:
        halvings += 1
    return halvings


def jpeg_size(data: bytes) -> Optional[Tuple[int, int]]:
    """(width, height) px of a baseline or progressive Huffman JPEG (SOF0..SOF2); None for
    others (arithmetic coding, lossless) and broken files."""
    at = 2
    while at + 4 <= len(data):
        if data[at] != 0xFF:
            return None
        marker = data[at + 1]
        if marker == 0xFF:            # fill byte
            at += 1
            continue
        if 0xD0 <= marker <= 0xD9 or marker == 0x01:   # markers without a length
            at += 2
            continue
        length = struct.unpack(">H", data[at + 2:at + 4])[0]
        if marker in (0xC0, 0xC1, 0xC2):
            if at + 9 > len(data):
                return None
            height, width = struct.unpack(">HH", data[at + 5:at + 9])
            return width, height
        if 0xC3 <= marker <= 0xCF and marker not in (0xC4, 0xC8, 0xCC):
            return None               # lossless or arithmetic coded: stb_image reads neither
        at += 2 + length
    return None


def halved_size(width: int, height: int, halvings: int) -> Tuple[int, int]:
    """(width, height) px of an image halved ``halvings`` times, each side rounded up and
    never below MIN_HALVED_SIDE (nor above the side it had)."""
    def side(n):
        return max(min(n, MIN_HALVED_SIDE), -(-n // (1 << halvings)))
    return side(width), side(height)


def halved_image(data: bytes, halvings: int) -> Tuple[bytes, str]:
    """(image bytes, ".png" or ".jpg") of the PNG or JPEG ``data`` halved ``halvings`` times
    (``halved_size``; box filtered), or ``data`` itself for 0 halvings. A JPEG stays a JPEG
    (quality 90), a PNG a PNG (RGB or RGBA as it was). ValueError if Pillow cannot read it."""
    suffix = ".png" if data[:4] == b"\x89PNG" else ".jpg"
    if halvings <= 0:
        return data, suffix
    from PIL import Image    # Pillow (python3-pil) only for a texture set over the budget
    try:
        with Image.open(io.BytesIO(data)) as image:
            image.load()
            mode = "RGBA" if "A" in image.getbands() and suffix == ".png" else "RGB"
            small = image.convert(mode).resize(
                halved_size(image.width, image.height, halvings), Image.BOX)
    except Exception as err:   # noqa: BLE001 - Pillow's many errors: one answer
        raise ValueError("cannot halve the image: %s" % err) from None
    out = io.BytesIO()
    if suffix == ".png":
        small.save(out, "PNG")
    else:
        small.save(out, "JPEG", quality=90)
    return out.getvalue(), suffix
