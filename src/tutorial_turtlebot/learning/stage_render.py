"""StageEnv's pictures (doc/learning.md, "Rendering"): the stage seen from above, drawn with
numpy alone, and a Tk window for render_mode "human".

``StageView`` draws an RGB image (rows x columns x 3, uint8) of a stage world: the world's
static shapes (walls, pillars, blocks) once into a background, then at each frame the moving
obstacles at their poses, the laser's rays (to their ranges; a ray with no return to the
laser's range_max, fainter), the goal (a dot, and a ring at the distance that counts as
reached), the robot (a disc of its footprint radius) and its heading (a line from its centre to
its rim). Shapes are drawn in plan, as upright: a box as its rectangle turned by its yaw, a
cylinder or a sphere as a disc; planes (the ground), meshes and polylines are not drawn.

Units and frames: metres and radians, every pose in the world frame of the stage world, a yaw
counter-clockwise from +x. The picture maps the world to pixels at a fixed scale (``scale``,
px per m) over the extent of the world's shapes and a margin: world +x to the right, +y up;
pixel (row, col) covers world x from ``left + col / scale`` and y down from
``top - row / scale``, so ``world_to_pixel`` puts pixel centres at whole numbers.

``StageRender`` is what StageEnv holds: the render mode's checks at construction (a missing
display fails there, in one line), the view (made at the first frame), the window (tkinter and
Pillow's ImageTk, imported only for "human"), or the robot's camera image instead.
"""
import importlib
import math
import os
import sys
import time
import warnings
from typing import Dict, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from ..errors import UserError
from ..robot_models import MODELS
from ..sim.devices.lidar import ray_directions
from ..sim.files.world_types import Shape, World
from ..sim.kinematics import transform_from_xyz_rpy, yaw_from_quat
from ..sim.world.spawn_check import footprint_radius
from .robotis_stages import GOAL_RANGE

RENDER_MODES = ("rgb_array", "human")
SIZE = 400                        # px: the picture is SIZE x SIZE
MARGIN = 0.15                     # m of floor around the world's shapes
GOAL_DOT = 0.05                   # m: radius of the goal's dot

# colours (R, G, B)
FLOOR = (244, 244, 240)
GRID = (222, 222, 216)            # a line every metre
STATIC = (96, 86, 78)             # the world's static shapes
MOVING = (60, 110, 200)           # the moving obstacles, where they are now
RAY_HIT = (40, 160, 60)           # a ray with a return, to its range
RAY_NONE = (180, 224, 186)        # a ray with no return, to range_max
GOAL = (215, 35, 35)
GOAL_ZONE = (240, 170, 170)       # the ring at GOAL_RANGE
ROBOT = (255, 150, 0)
HEADING = (20, 20, 20)

Plan = Tuple[float, float, float]   # x, y (m), yaw (rad) of a frame seen from above


class Footprint(NamedTuple):
    """A shape seen from above: a disc, or a rectangle turned by ``yaw``, about (x, y)."""

    disc: bool
    half_x: float     # m: a rectangle's half length along its own x; a disc's radius
    half_y: float     # m: a rectangle's half width along its own y; a disc's radius
    x: float          # m, in the frame it is given in
    y: float
    yaw: float        # rad

    def reach(self) -> Tuple[float, float]:
        """(half extent along x, along y) of its bounding box in its frame (m)."""
        if self.disc:
            return self.half_x, self.half_x
        c, s = abs(math.cos(self.yaw)), abs(math.sin(self.yaw))
        return self.half_x * c + self.half_y * s, self.half_x * s + self.half_y * c

    def placed(self, frame: Plan) -> "Footprint":
        """This footprint, given in ``frame``, in the frame ``frame`` is given in."""
        fx, fy, fyaw = frame
        c, s = math.cos(fyaw), math.sin(fyaw)
        return self._replace(x=fx + c * self.x - s * self.y, y=fy + s * self.x + c * self.y,
                             yaw=self.yaw + fyaw)


def footprint_of(shape: Shape) -> Optional[Footprint]:
    """A box's, cylinder's or sphere's footprint in the world; None for any other kind."""
    x, y, _, _, _, yaw = shape.pose
    if shape.kind == "box":
        return Footprint(False, shape.size[0] / 2, shape.size[1] / 2, x, y, yaw)
    if shape.kind in ("cylinder", "sphere"):
        return Footprint(True, shape.size[0], shape.size[0], x, y, yaw)
    return None


class MovingShape(NamedTuple):
    """A shape of a model that moves: its footprint in its model's frame."""

    model: str
    footprint: Footprint


# --- drawing: pixel units, (col, row) floats with pixel centres at whole numbers ---------------

def _window(image: np.ndarray, col: float, row: float, reach: float):
    """(row offsets, col offsets, the image's view) of the pixels within ``reach`` px of
    (col, row) in both directions, clipped to the image; None if none is in it."""
    height, width = image.shape[:2]
    r0, r1 = max(int(math.floor(row - reach)), 0), min(int(math.ceil(row + reach)) + 1, height)
    c0, c1 = max(int(math.floor(col - reach)), 0), min(int(math.ceil(col + reach)) + 1, width)
    if r0 >= r1 or c0 >= c1:
        return None
    return (np.arange(r0, r1)[:, None] - row, np.arange(c0, c1)[None, :] - col,
            image[r0:r1, c0:c1])


def fill_disc(image: np.ndarray, col: float, row: float, radius: float, colour,
              inner: float = -1.0) -> None:
    """The pixels whose centres lie within ``radius`` px of (col, row) (and beyond ``inner``
    px: a ring) in ``colour``."""
    window = _window(image, col, row, radius)
    if window is None:
        return
    rows, cols, view = window
    d2 = rows * rows + cols * cols
    inside = d2 <= radius * radius
    if inner >= 0:
        inside &= d2 > inner * inner
    view[inside] = colour


def fill_rectangle(image: np.ndarray, col: float, row: float, half_x: float, half_y: float,
                   yaw: float, colour) -> None:
    """A rectangle of half sides ``half_x``, ``half_y`` px about (col, row), its x axis turned
    ``yaw`` rad counter-clockwise from the picture's right (world +x)."""
    window = _window(image, col, row, math.hypot(half_x, half_y))
    if window is None:
        return
    rows, cols, view = window
    c, s = math.cos(yaw), math.sin(yaw)
    along = cols * c - rows * s          # (rows grow downward: world y is -rows)
    across = -cols * s - rows * c
    view[(np.abs(along) <= half_x) & (np.abs(across) <= half_y)] = colour


def draw_segments(image: np.ndarray, starts: np.ndarray, ends: np.ndarray, colour) -> None:
    """One-pixel lines (N x 2 (col, row) arrays) from ``starts`` to ``ends``: a pixel at least
    at every column or row the longest crosses, each line ending on the pixel its end is in."""
    if len(starts) == 0:
        return
    height, width = image.shape[:2]
    spans = ends - starts
    t = np.linspace(0.0, 1.0, int(math.ceil(np.abs(spans).max())) + 2)[:, None, None]
    cols, rows = np.rint(starts[None] + t * spans[None]).astype(np.intp).reshape(-1, 2).T
    keep = (cols >= 0) & (cols < width) & (rows >= 0) & (rows < height)
    image[rows[keep], cols[keep]] = colour


# --- the view -----------------------------------------------------------------------------------

class StageView:
    """The top-down picture of one world: its fixed mapping, its background, its frames."""

    def __init__(self, world: World, robot_radius: float, size: int = SIZE,
                 margin: float = MARGIN, goal_radius: float = GOAL_RANGE):
        """``world``: the loaded world (its collisions are drawn); ``robot_radius`` (m): the
        robot's footprint; ``goal_radius`` (m): the ring about the goal."""
        self.robot_radius = robot_radius
        self.goal_radius = goal_radius
        statics, moving, spawn = [], [], {m.name: m.pose for m in world.model_specs}
        for shape in world.collisions:
            footprint = footprint_of(shape)
            if footprint is None:
                continue
            if shape.static:
                statics.append(footprint)
                continue
            model = shape.name.split("::", 1)[0]
            mx, my, _, _, _, myaw = spawn[model]
            c, s = math.cos(myaw), math.sin(myaw)
            dx, dy = footprint.x - mx, footprint.y - my
            moving.append((footprint, MovingShape(model, footprint._replace(
                x=c * dx + s * dy, y=-s * dx + c * dy, yaw=footprint.yaw - myaw))))
        self.moving = tuple(m for _, m in moving)
        self.moving_models = tuple(dict.fromkeys(m.model for m in self.moving))
        # the extent: every shape drawn (the moving at their spawn), else the 4 m arena
        boxes = [(f.x - rx, f.y - ry, f.x + rx, f.y + ry)
                 for f in statics + [f for f, _ in moving] for rx, ry in [f.reach()]]
        boxes = boxes or [(-2.0, -2.0, 2.0, 2.0)]
        x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
        x1, y1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
        self.size = size
        self.scale = size / (max(x1 - x0, y1 - y0) + 2 * margin)      # px per m
        self.left = (x0 + x1) / 2 - size / (2 * self.scale)          # m: the picture's edges
        self.top = (y0 + y1) / 2 + size / (2 * self.scale)
        self.background = self._background(statics)

    def world_to_pixel(self, x, y):
        """(col, row) of world point(s) (m): fractional, pixel centres at whole numbers."""
        return (x - self.left) * self.scale - 0.5, (self.top - y) * self.scale - 0.5

    def _background(self, statics) -> np.ndarray:
        image = np.empty((self.size, self.size, 3), np.uint8)
        image[:] = FLOOR
        right, bottom = self.left + self.size / self.scale, self.top - self.size / self.scale
        for x in range(math.ceil(self.left), math.floor(right) + 1):
            col = int(round(self.world_to_pixel(x, 0.0)[0]))
            if 0 <= col < self.size:
                image[:, col] = GRID
        for y in range(math.ceil(bottom), math.floor(self.top) + 1):
            row = int(round(self.world_to_pixel(0.0, y)[1]))
            if 0 <= row < self.size:
                image[row, :] = GRID
        for footprint in statics:
            self._fill(image, footprint, STATIC)
        return image

    def _fill(self, image: np.ndarray, footprint: Footprint, colour) -> None:
        col, row = self.world_to_pixel(footprint.x, footprint.y)
        if footprint.disc:
            fill_disc(image, col, row, footprint.half_x * self.scale, colour)
        else:
            fill_rectangle(image, col, row, footprint.half_x * self.scale,
                           footprint.half_y * self.scale, footprint.yaw, colour)

    def draw(self, robot: Plan, goal: Sequence[float], laser_origin: Sequence[float] = (0, 0),
             ray_directions: Optional[np.ndarray] = None,
             ranges: Optional[Sequence[float]] = None, range_max: float = math.inf,
             model_poses: Optional[Dict[str, Plan]] = None) -> np.ndarray:
        """A new picture: the background, then the moving shapes of the models in
        ``model_poses`` (name: plan pose of its model frame; others are left out), the rays
        from ``laser_origin`` (x, y) along ``ray_directions`` (N x 2, world plan) to
        ``ranges`` (m, a scan as the laser gives it: +inf no return, drawn to ``range_max``;
        -inf and NaN not drawn), the goal (x, y) and the robot at ``robot``."""
        image = self.background.copy()
        for shape in self.moving:
            frame = (model_poses or {}).get(shape.model)
            if frame is not None:
                self._fill(image, shape.footprint.placed(frame), MOVING)
        if ranges is not None and ray_directions is not None:
            self._rays(image, laser_origin, ray_directions, np.asarray(ranges, float), range_max)
        col, row = self.world_to_pixel(goal[0], goal[1])
        fill_disc(image, col, row, self.goal_radius * self.scale, GOAL_ZONE,
                  inner=self.goal_radius * self.scale - 1.5)
        fill_disc(image, col, row, max(GOAL_DOT * self.scale, 1.0), GOAL)
        x, y, yaw = robot
        col, row = self.world_to_pixel(x, y)
        reach = self.robot_radius * self.scale
        fill_disc(image, col, row, max(reach, 1.0), ROBOT)
        half = self.robot_radius / 2      # the heading: a bar 3 px wide, centre to rim
        col, row = self.world_to_pixel(x + half * math.cos(yaw), y + half * math.sin(yaw))
        fill_rectangle(image, col, row, reach / 2, 1.5, yaw, HEADING)
        return image

    def _rays(self, image, origin, directions, ranges, range_max) -> None:
        start = np.array(self.world_to_pixel(origin[0], origin[1]))
        no_return = ranges == math.inf
        for chosen, colour in ((no_return, RAY_NONE), (np.isfinite(ranges) & (ranges > 0),
                                                       RAY_HIT)):
            lengths = np.where(no_return, range_max, ranges)[chosen]
            if not np.isfinite(lengths).all():    # (no return, and no range_max to draw to)
                continue
            ends = np.asarray(origin[:2])[None] + directions[chosen] * lengths[:, None]
            cols, rows = self.world_to_pixel(ends[:, 0], ends[:, 1])
            draw_segments(image, np.repeat(start[None], len(ends), 0),
                          np.stack([cols, rows], 1), colour)


# --- the env's part -----------------------------------------------------------------------------

def check_display(environ=os.environ) -> None:
    """UserError (one line) unless a Tk window can be tried: $DISPLAY set, tkinter and Pillow's
    ImageTk importable."""
    if not environ.get("DISPLAY"):
        raise UserError("render_mode='human' needs a display and $DISPLAY is not set: use "
                        "render_mode='rgb_array', or run under xvfb-run")
    try:
        # whether they import, only: HumanWindow imports them again to use them
        importlib.import_module("tkinter")
        importlib.import_module("PIL.ImageTk")
    except ImportError as err:
        raise UserError("render_mode='human' needs tkinter and Pillow's ImageTk (Debian: "
                        "python3-tk python3-pil.imagetk): %s" % err) from None


class HumanWindow:
    """A Tk window showing one image after another, at most ``fps`` a wall second (so an env
    rendered in it runs at real time). Closed by the user, it shows nothing more."""

    def __init__(self, title: str, fps: float):
        import tkinter
        from PIL import Image, ImageTk
        self._tk, self._image, self._image_tk = tkinter, Image, ImageTk
        try:
            self._root = tkinter.Tk()
        except tkinter.TclError as err:
            raise UserError("render_mode='human': no window on display %r: %s"
                            % (os.environ.get("DISPLAY"), err)) from None
        self._root.title(title)
        self._root.protocol("WM_DELETE_WINDOW", self.close)
        self._label = tkinter.Label(self._root)
        self._label.pack()
        self._period = 1.0 / fps
        self._due = None

    @property
    def is_open(self) -> bool:
        return self._root is not None

    def show(self, image: np.ndarray) -> None:
        """Put ``image`` (HxWx3 uint8) in the window, waiting until its time has come."""
        if self._root is None:
            return
        now = time.monotonic()
        if self._due is not None and now < self._due:
            time.sleep(self._due - now)
        self._due = max(now, self._due or now) + self._period
        try:
            photo = self._image_tk.PhotoImage(self._image.fromarray(image), master=self._root)
            self._label.configure(image=photo)
            self._label.image = photo      # (Tk shows it only while Python holds it)
            self._root.update()
        except self._tk.TclError:          # the window went away
            self._root = None

    def close(self) -> None:
        if self._root is not None:
            try:
                self._root.destroy()
            except self._tk.TclError:
                pass
            self._root = None


class StageRender:
    """StageEnv's rendering: checks the mode at construction, draws at each frame."""

    def __init__(self, render_mode: Optional[str], render_camera: bool, model: str,
                 fps: float, title: str = "TurtleBot3 stage"):
        """``render_mode``: None, "rgb_array" or "human" (ValueError else; without a display,
        human mode says so in one line on stderr and shows nothing); ``render_camera``: the
        robot's camera image instead of the top-down picture (ValueError for a model without a
        camera)."""
        if render_mode is not None and render_mode not in RENDER_MODES:
            raise ValueError("render_mode %r: the modes are None, %s"
                             % (render_mode, ", ".join(repr(m) for m in RENDER_MODES)))
        spec = MODELS.get(model)
        if render_camera and spec is not None and not spec.carries_camera:
            raise ValueError("render_camera=True needs a model with a camera (%s); %r has none"
                             % (", ".join(m for m, s in MODELS.items() if s.carries_camera),
                                model))
        self.mode, self.camera, self.fps, self.title = render_mode, render_camera, fps, title
        # human mode where no window can be had: said in one line, then nothing is shown (the
        # env runs on: Gymnasium's env checker makes every declared mode, display or not)
        self.showing = True
        if render_mode == "human":
            try:
                check_display()
            except UserError as err:
                self._no_window(err)
        self.view: Optional[StageView] = None
        self.window: Optional[HumanWindow] = None
        # (4x4 pose of the laser in the robot's root link, its rays there, range_max m)
        self._laser = None

    def frame(self, sim, robot, goal: Sequence[float],
              ranges: Optional[Sequence[float]]) -> Optional[np.ndarray]:
        """The picture now (``render_mode`` "rgb_array"), or None after showing it ("human");
        ``sim``: the Simulation, ``robot`` its SimRobot, ``goal`` (x, y) m, ``ranges``: the
        last observation's scan (None: no rays)."""
        if self.mode == "human" and not self.showing:
            return None
        if self.mode is None:
            warnings.warn("render() draws nothing with render_mode None: make the env with "
                          "render_mode='rgb_array' or 'human'", stacklevel=3)
            return None
        image = (robot.camera_image()[0] if self.camera
                 else self.top_down(sim, robot, goal, ranges))
        if self.mode == "rgb_array":
            return image
        if self.window is None:
            try:
                self.window = HumanWindow(self.title, self.fps)
            except UserError as err:
                self._no_window(err)
                return None
        self.window.show(image)
        return None

    def _no_window(self, err: UserError) -> None:
        sys.stderr.write("%s; nothing is shown\n" % err)
        self.showing = False

    def top_down(self, sim, robot, goal, ranges) -> np.ndarray:
        """StageView's picture of ``sim`` now: the robot at its true pose, the rays from its
        laser's."""
        if self.view is None:
            self.view = StageView(sim.world, footprint_radius(robot.description))
            sensor = robot.laser_sensor
            if sensor is not None and robot.laser is not None:
                in_root = robot.body.frame_in_footprint(sensor.link) @ transform_from_xyz_rpy(
                    sensor.pose[:3], sensor.pose[3:])
                self._laser = (in_root, ray_directions(robot.laser), robot.laser.range_max)
        (x, y, _), orientation = robot.ground_truth()
        rays = {}
        if self._laser is not None and ranges is not None:
            in_root, directions, range_max = self._laser
            origin, rotation = robot.body.pose_in_world(in_root)
            rays = dict(laser_origin=origin[:2], ray_directions=(directions @ rotation.T)[:, :2],
                        ranges=ranges, range_max=range_max)
        poses = {}
        for name in self.view.moving_models:
            if name in sim.models:
                (mx, my, _), quat = sim.models.get(name).pose()
                poses[name] = (mx, my, yaw_from_quat(quat))
        return self.view.draw((x, y, yaw_from_quat(orientation)), goal, model_poses=poses,
                              **rays)

    def close(self) -> None:
        if self.window is not None:
            self.window.close()
