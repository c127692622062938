"""Camera images rendered by pybullet, and the renderer's state per client. Knows nothing of ROS.

- ``enable_egl`` / ``disable_egl``: pybullet's EGL renderer plugin (Mesa or a GPU), loaded right
  after ``pybullet.connect`` and before any body exists; ``CameraRenderer`` falls back to
  pybullet's TinyRenderer (CPU) where it does not load.
- ``note_textures``: what the builders of textured visuals tell the renderer of a client
  (textures change the OpenGL shader); their sizes are texture_budget's.
- ``validate_spec``: the cameras the renderer can make (UserError, one line, for others).
- ``CameraRenderer.render``: the RGB image and the depth image of a camera (devices.camera's
  spec) whose optical frame (z forward, x right, y down) has a given world pose.

Images are row-major, row 0 at the top, column 0 at the left (sensor_msgs/Image order).
Units: metres, radians.
"""
import contextlib
import importlib.util
import math
import subprocess
import sys
from typing import List, Optional, Sequence, Tuple

import numpy as np

from ...errors import UserError
from ..files import limits
from . import texture_budget
from .bullet import pybullet, quiet_output
from .client import Client
from . import view_culling
from ..files.plugins.robot_plugin_types import CameraSpec

# pybullet's OpenGL renderers read images from a buffer of this size (EGL: 1024 x 768).
OPENGL_BUFFER = (1024, 768)
# A z-buffer value at or above this is "nothing drawn": TinyRenderer leaves 1 - 6e-8 there; with
# near 0.03 m and far 100 m it is the depth of 99.7 m.
EMPTY_ZBUFFER = 1.0 - 1e-6
# TinyRenderer samples pixel (col, row) at (col, row + 1) in top-down image coordinates
# (measured), half a pixel left of and below the centre that OpenGL and the
# CameraInfo's pinhole use; its frustum is moved by this many pixels (right, up) to match.
TINY_RENDERER_SHIFT = (0.5, 0.5)
# Gazebo's scene background of the TurtleBot3 worlds (<background>0.7 0.7 0.7 1</background>):
# pixels that see no surface get it, with either renderer.
BACKGROUND_RGB = (178, 178, 178)
# Lighting: the direction towards Gazebo's sun (its light travels along (-0.5, 0.1, -0.9)).
# EGL's shader takes no coefficients (it has its own ambient, diffuse and a specular glint);
# TinyRenderer's are set so that its images look like EGL's, white pillars standing out from the
# 0.7 grey floor. No shadows with either renderer.
LIGHT_DIRECTION = (0.5, -0.1, 0.9)
LIGHT_AMBIENT, LIGHT_DIFFUSE, LIGHT_SPECULAR = 0.8, 0.2, 0.0
EGL_PROBE_TIMEOUT = 30.0         # s for the subprocess that checks that EGL renders here
# The EGL plugin prints "ven = <vendor>" at each of its first images (measured: two, whatever
# their size and flags): enable_egl draws them, silenced.
EGL_CHATTY_IMAGES = 2

MAX_IMAGE_SIDE = limits.MAX_IMAGE_SIDE   # px: larger images are refused
Vector = Sequence[float]


def validate_spec(spec: CameraSpec) -> None:
    """Raise UserError (one line) for a camera the renderer cannot make."""
    for name in ("width", "height"):
        value = getattr(spec, name)
        if isinstance(value, bool) or not isinstance(value, int) \
                or not 0 < value <= MAX_IMAGE_SIDE:
            raise UserError("camera %s %r px must be a whole number from 1 to %d"
                            % (name, value, MAX_IMAGE_SIDE))
    if not (isinstance(spec.hfov, (int, float)) and 0.0 < spec.hfov < math.pi):
        raise UserError("camera horizontal_fov %r rad must be between 0 and pi (180 degrees), "
                        "both excluded" % (spec.hfov,))
    if not (isinstance(spec.near, (int, float)) and isinstance(spec.far, (int, float))
            and 0.0 < spec.near < spec.far < math.inf):
        raise UserError("camera clip near %r m and far %r m must satisfy 0 < near < far"
                        % (spec.near, spec.far))
    if not (isinstance(spec.rate, (int, float)) and 0.0 < spec.rate < math.inf):
        raise UserError("camera update rate %r Hz must be a positive number" % (spec.rate,))


# --- the EGL plugin ------------------------------------------------------------------------------

_PROBE = r"""
import sys
import numpy as np
import pybullet as p
p.connect(p.DIRECT)    # the process's only client: every call below is to it
if p.loadPlugin(sys.argv[1], "_eglRendererPlugin") < 0:
    sys.exit(3)
box = p.createVisualShape(p.GEOM_BOX, halfExtents=(1, 1, 1), rgbaColor=(0, 1, 0, 1))
p.createMultiBody(0, -1, box, basePosition=(3, 0, 0))
view = p.computeViewMatrix((0, 0, 0), (1, 0, 0), (0, 0, 1))
proj = p.computeProjectionMatrixFOV(60, 1, 0.1, 10)
rgba = p.getCameraImage(8, 8, view, proj, renderer=p.ER_BULLET_HARDWARE_OPENGL)[2]
r, g, b = np.asarray(rgba, dtype=np.uint8).reshape(8, 8, 4)[4, 4, :3].astype(int)
sys.exit(0 if g > 100 and r < 60 and b < 60 else 4)
"""

_egl_works: Optional[bool] = None     # the probe's answer, once per process


def egl_plugin_path() -> Optional[str]:
    """File of pybullet's eglRenderer plugin, or None where this pybullet has none."""
    try:
        spec = importlib.util.find_spec("eglRenderer")
    except (ImportError, ValueError):
        return None
    return spec.origin if spec is not None else None


def egl_available() -> bool:
    """Whether the EGL plugin loads and renders on this machine.

    The plugin calls exit() when EGL cannot start (no libEGL, no device), so it is tried once
    in a child process; the answer is kept for the rest of this process.
    """
    global _egl_works
    if _egl_works is None:
        path = egl_plugin_path()
        if path is None:
            _egl_works = False
        else:
            try:
                done = subprocess.run([sys.executable, "-c", _PROBE, path],
                                      stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, timeout=EGL_PROBE_TIMEOUT)
                _egl_works = done.returncode == 0
            except (OSError, subprocess.SubprocessError):
                _egl_works = False
    return _egl_works


def enable_egl(client: Client) -> bool:
    """Load the EGL renderer into pybullet ``client``; True if it is in use.

    Call it right after ``pybullet.connect`` (DIRECT) and before any body is created: the
    plugin draws only the bodies created after it. Never raises; False means TinyRenderer.
    Loading it again into the same client is harmless (pybullet keeps one). Call
    ``disable_egl`` before disconnecting. The plugin prints
    a few lines (GL vendor, version) straight to file descriptor 1 when it loads, and
    "ven = <GL vendor>" at each of its first two images (each makes a render target): it is
    loaded and draws two empty 1 x 1 images here, with what they print silenced.
    """
    if not egl_available():
        return False
    with quiet_output():
        try:
            plugin = client.loadPlugin(egl_plugin_path(), "_eglRendererPlugin")
        except pybullet.error:
            return False
        if plugin < 0:
            return False
        for _ in range(EGL_CHATTY_IMAGES):
            client.getCameraImage(1, 1, renderer=pybullet.ER_BULLET_HARDWARE_OPENGL,
                                  flags=pybullet.ER_NO_SEGMENTATION_MASK)
    client.egl_plugin = plugin
    return True


def disable_egl(client: Client) -> None:
    """Unload the EGL plugin of ``client`` (before it is disconnected); no-op without. Also
    forgets ``note_textures``, texture_budget and view_culling of that client."""
    client.textured = False
    texture_budget.forget(client)
    view_culling.forget(client)
    plugin, client.egl_plugin = client.egl_plugin, None
    if plugin is not None:
        try:
            client.unloadPlugin(plugin)
        except pybullet.error:
            pass    # the client is already gone, and the plugin with it


def note_textures(client: Client) -> None:
    """Say that ``client`` has (or may have) a textured visual: its OpenGL images are drawn by
    the shader that maps textures by their coordinates from then on (see CameraRenderer).
    Until ``disable_egl`` of that client."""
    client.textured = True


def egl_enabled(client: Client) -> bool:
    """Whether ``enable_egl`` loaded the plugin into ``client``."""
    return client.egl_plugin is not None


# --- rendering -----------------------------------------------------------------------------------

def view_matrix(position: Vector, rotation) -> List[float]:
    """pybullet's (OpenGL, column-major) view matrix of an optical frame at world ``position``
    with world 3x3 ``rotation`` (columns: x right, y down, z forward)."""
    rot = np.asarray(rotation, dtype=float).reshape(3, 3)
    # OpenGL's camera looks along its -z with y up: x_gl = x, y_gl = -y, z_gl = -z.
    gl = rot * np.array([1.0, -1.0, -1.0])
    view = np.eye(4)
    view[:3, :3] = gl.T
    view[:3, 3] = -gl.T @ np.asarray(position, dtype=float)
    return view.T.ravel().tolist()


class CameraRenderer:
    """Renders one camera (``spec``) in pybullet ``client``.

    ``use_egl``: pybullet's hardware OpenGL renderer (the EGL plugin, or the window of a GUI
    client); otherwise TinyRenderer. Where the EGL plugin is loaded it renders every request
    whatever the flag. OpenGL draws into a 1024 x 768 buffer and would stretch a larger image
    from it, so a larger image is drawn as tiles of at most that size, each with its part of the
    frustum. Every body of the client is drawn: the camera frames of the TurtleBot3 URDFs sit
    where the near clip plane (3 cm) leaves the robot out of view. (With the EGL plugin and the
    shadow-map shader, the static bodies wholly out of view are left out of an image, which
    stays the same: view_culling.)
    """

    def __init__(self, client: Client, spec: CameraSpec, use_egl: bool,
                 background: Tuple[int, int, int] = BACKGROUND_RGB, skip_shadows: bool = True):
        """``skip_shadows`` (OpenGL only): draw through pybullet's projective-texture shader,
        which has no shadow-map pass: 2 to 10 times faster on Mesa, and no shadow artefacts. It
        maps every texture as projected from the camera, not by its coordinates (measured: a
        textured face comes out in one texel's colour), so it is used only while no textured
        visual is in the client (``note_textures``); then the usual shader draws, with
        ``shadow=0`` (measured, Mesa, 640 x 480 in turtlebot3_world: 35 ms an image instead of
        12). TinyRenderer maps textures by their coordinates either way."""
        validate_spec(spec)
        self.client = client
        self.spec = spec
        self.use_egl = bool(use_egl)
        self.background = np.array(background, dtype=np.uint8)
        self._background_rgba = np.frombuffer(bytes(self.background) + b"\xff",
                                              dtype=np.uint32)[0]
        self._renderer = (pybullet.ER_BULLET_HARDWARE_OPENGL if self.use_egl
                          else pybullet.ER_TINY_RENDERER)
        opengl = self.use_egl or egl_enabled(client)
        if opengl:
            self._tiles = _tiles(spec, *OPENGL_BUFFER)
        else:  # TinyRenderer samples each pixel at its corner: move the frustum half a pixel
            self._tiles = _tiles(spec, spec.width, spec.height, TINY_RENDERER_SHIFT)
        self._projective = opengl and skip_shadows
        # With the shadow-map shader (a textured client) the static bodies out of view are left
        # out of an EGL image (view_culling). Public: None draws every body (the bench's figure
        # of the cost without it).
        self.view_culling = (view_culling.ViewCulling(client, spec.hfov,
                                                      spec.height / spec.width, spec.near,
                                                      spec.far, LIGHT_DIRECTION)
                             if egl_enabled(client) else None)

    @property
    def renderer_name(self) -> str:
        return "EGL (OpenGL)" if self.use_egl else "TinyRenderer (CPU)"

    @property
    def tile_count(self) -> int:
        """How many renders make one image (1 unless OpenGL draws a large image in tiles)."""
        return len(self._tiles)

    def render(self, position: Vector, rotation,
               depth: bool = False) -> Tuple[np.ndarray, Optional[np.ndarray]]:
        """(rgb, depth) seen from an optical frame at world ``position`` with world 3x3
        ``rotation`` (z forward, x right, y down).

        rgb: uint8 (height, width, 3), C-contiguous, right side up; background grey where no
        surface is within the far clip. depth (only with ``depth=True``, else None): float32
        (height, width), metres along the optical axis (not along the ray), +inf where no
        surface is within the far clip.
        """
        spec = self.spec
        view = view_matrix(position, rotation)
        with self._left_out(position, rotation):
            if len(self._tiles) == 1:
                rgba, zbuffer = self._render_tile(view, *self._tiles[0])
            else:
                rgba = np.empty((spec.height, spec.width, 4), dtype=np.uint8)
                zbuffer = np.empty((spec.height, spec.width), dtype=np.float32)
                for tile in self._tiles:
                    r0, r1, c0, c1 = tile[0]
                    rgba[r0:r1, c0:c1], zbuffer[r0:r1, c0:c1] = self._render_tile(view, *tile)
        # Background where nothing was drawn: one 32-bit store per pixel, in place.
        np.copyto(rgba.view(np.uint32)[:, :, 0], self._background_rgba,
                  where=zbuffer >= EMPTY_ZBUFFER)
        rgb = np.ascontiguousarray(rgba[:, :, :3])
        if not depth:
            return rgb, None
        return rgb, zbuffer_to_depth(zbuffer, spec.near, spec.far)

    def _left_out(self, position, rotation):
        """The context an image is drawn in: with the shadow-map shader (EGL, a textured
        client), the fixed bodies it cannot show are left out (view_culling); else nothing."""
        projective = self._projective and not self.client.textured
        if self.view_culling is None or projective:
            return contextlib.nullcontext()
        return self.view_culling.hidden_outside(position, rotation)

    def _render_tile(self, view, rows_cols, projection) -> Tuple[np.ndarray, np.ndarray]:
        """(rgba uint8 h x w x 4, z-buffer float32 h x w) of one tile, writable arrays."""
        r0, r1, c0, c1 = rows_cols
        width, height = c1 - c0, r1 - r0
        flags = pybullet.ER_NO_SEGMENTATION_MASK
        extra = {}
        if self._projective and not self.client.textured:
            flags |= pybullet.ER_USE_PROJECTIVE_TEXTURE
            extra = {"projectiveTextureView": view, "projectiveTextureProj": projection}
        _, _, rgba, zbuffer, _ = self.client.getCameraImage(
            width, height, view, projection,
            lightDirection=LIGHT_DIRECTION, shadow=0, lightAmbientCoeff=LIGHT_AMBIENT,
            lightDiffuseCoeff=LIGHT_DIFFUSE, lightSpecularCoeff=LIGHT_SPECULAR,
            renderer=self._renderer, flags=flags, **extra)
        rgba = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)
        zbuffer = np.asarray(zbuffer, dtype=np.float32).reshape(height, width)
        if not rgba.flags.writeable:
            rgba = rgba.copy()
        return rgba, zbuffer


def _tiles(spec: CameraSpec, max_width: int, max_height: int,
           shift: Tuple[float, float] = (0.0, 0.0)):
    """[((row0, row1, col0, col1), projection)]: the image cut into equal tiles of at most
    max_width x max_height px, each with the off-centre projection of its part of the frustum,
    moved by ``shift`` pixels (right, up)."""
    nx = -(-spec.width // max_width)
    ny = -(-spec.height // max_height)
    cols = [spec.width * i // nx for i in range(nx + 1)]
    rows = [spec.height * j // ny for j in range(ny + 1)]
    half_w = spec.near * math.tan(spec.hfov / 2.0)        # at the near plane, m
    half_h = half_w * spec.height / spec.width
    dx = shift[0] * 2.0 * half_w / spec.width
    dy = shift[1] * 2.0 * half_h / spec.height
    tiles = []
    for r0, r1 in zip(rows, rows[1:]):
        for c0, c1 in zip(cols, cols[1:]):
            left = -half_w + 2.0 * half_w * c0 / spec.width
            right = -half_w + 2.0 * half_w * c1 / spec.width
            top = half_h - 2.0 * half_h * r0 / spec.height
            bottom = half_h - 2.0 * half_h * r1 / spec.height
            projection = pybullet.computeProjectionMatrix(left + dx, right + dx, bottom + dy,
                                                          top + dy, spec.near, spec.far)
            tiles.append(((r0, r1, c0, c1), projection))
    return tiles


def zbuffer_to_depth(zbuffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """OpenGL z-buffer values (0 at ``near``, 1 at ``far``) to metres along the optical axis
    (float32); +inf where nothing was drawn.

    depth = far near / (far - (far - near) z), computed as near + (far - near)(1 - z) in the
    denominator: 1 - z is exact in float32 for z >= 0.5, so nothing cancels.
    """
    z = np.asarray(zbuffer, dtype=np.float32)
    depth = np.subtract(np.float32(1.0), z, dtype=np.float32)
    depth *= np.float32(far - near)
    depth += np.float32(near)
    np.divide(np.float32(far * near), depth, out=depth)
    depth[z >= EMPTY_ZBUFFER] = np.inf
    return depth


# --- message payloads ----------------------------------------------------------------------------
