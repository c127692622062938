"""Actors moved along their scripts in sim time, as Gazebo 11 moves them. No ROS.

An actor (files.world_types.Actor) is a model of the world (world_models: its visual bodies,
listed in /gazebo/model_states after the models, as Gazebo's World::LoadEntities loads actors
after models). ``ActorMotion`` plays its ``<script>`` as gazebo/physics/Actor.cc's Update does:

- a new pose at most every 1/30 s of sim time (the first at 1/30 s), none before
  ``delay_start`` has passed since the script started (at sim time 0, or at a reset); a script
  that does not ``auto_start`` never plays, and the actor stands at its ``<pose>``;
- the script's trajectories play one after the other, each for the time of its last waypoint;
  at the end a looping script starts again from the frame's time (and waits its delay again),
  one that does not loop stops where its last frame put it;
- within a trajectory the pose is gz::common::PoseAnimation's (``PoseCurve``): the position on
  a cubic Hermite spline through the waypoints with Catmull-Rom tangents times (1 - tension)
  (gz::math::Spline, closed when the first and last points are equal), the orientation by
  squad between the waypoints with Shoemake's tangents (gz::math::RotationSpline,
  Quaternion::Squad on the shortest path).

Not done here: skeleton animation (the actor's skin is drawn as its file is written), a skin
animation's root motion (Gazebo adds the root bone's pose to the trajectory's; it reports that
bone's pose in model_states, about 1 m higher for its stock people), plugins driving an actor.

Poses are ((x, y, z), (qx, qy, qz, qw)) in the world frame; times in ns of sim time.
"""
import math
from typing import Dict, List, Optional, Sequence, Tuple

from ..files.world_types import Actor, Trajectory, World
from ..kinematics import quat_from_rpy
from . import reference_frames as rf
from .reference_frames import Pose

FRAME_PERIOD_S = 1.0 / 30.0   # Actor::Update refreshes at most at 30 Hz of sim time
_EPS = 1e-6                   # gz::math::equal's default tolerance
Quat = Tuple[float, float, float, float]   # (w, x, y, z) here, as gz::math::Quaterniond
Vec = Tuple[float, float, float]


# --- quaternions as gz::math::Quaterniond computes them --------------------------------------

def _mul(a: Quat, b: Quat) -> Quat:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def _inverse(q: Quat) -> Quat:
    s = sum(v * v for v in q)
    if abs(s) <= _EPS:
        return (1.0, 0.0, 0.0, 0.0)
    return (q[0] / s, -q[1] / s, -q[2] / s, -q[3] / s)


def _log(q: Quat) -> Quat:
    if abs(q[0]) < 1.0:
        angle = math.acos(q[0])
        sin = math.sin(angle)
        if abs(sin) >= 1e-3:
            k = angle / sin
            return (0.0, k * q[1], k * q[2], k * q[3])
    return (0.0, q[1], q[2], q[3])


def _exp(q: Quat) -> Quat:
    angle = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    sin = math.sin(angle)
    k = sin / angle if abs(sin) >= 1e-3 else 1.0
    return (math.cos(angle), k * q[1], k * q[2], k * q[3])


def _scaled(q: Quat, f: float) -> Quat:
    return (q[0] * f, q[1] * f, q[2] * f, q[3] * f)


def _added(a: Quat, b: Quat) -> Quat:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3])


def _slerp(t: float, p: Quat, q: Quat, shortest: bool = False) -> Quat:
    cos = sum(a * b for a, b in zip(p, q))
    if cos < 0.0 and shortest:
        cos, q = -cos, _scaled(q, -1.0)
    if abs(cos) < 1 - 1e-3:
        sin = math.sqrt(1 - cos * cos)
        angle = math.atan2(sin, cos)
        return _added(_scaled(p, math.sin((1.0 - t) * angle) / sin),
                      _scaled(q, math.sin(t * angle) / sin))
    mixed = _added(_scaled(p, 1.0 - t), _scaled(q, t))
    norm = math.sqrt(sum(v * v for v in mixed))
    return _scaled(mixed, 1.0 / norm) if norm > 0 else (1.0, 0.0, 0.0, 0.0)


def _squad(t: float, p: Quat, a: Quat, b: Quat, q: Quat) -> Quat:
    return _slerp(2.0 * t * (1.0 - t), _slerp(t, p, q, True), _slerp(t, a, b))


def _equal(a: Sequence[float], b: Sequence[float], tol: float) -> bool:
    return all(abs(u - v) <= tol for u, v in zip(a, b))


# --- one trajectory as a curve ----------------------------------------------------------------

class PoseCurve:
    """gz::common::PoseAnimation of one trajectory: the pose at a time from its start."""

    def __init__(self, trajectory: Trajectory):
        points = trajectory.waypoints
        self.times = [w.time for w in points]
        self.length = trajectory.duration
        self.positions: List[Vec] = [tuple(w.pose[:3]) for w in points]
        self.rotations: List[Quat] = []
        for w in points:
            x, y, z, qw = quat_from_rpy(*w.pose[3:])
            self.rotations.append((qw, x, y, z))
        self.tangents = self._position_tangents(1.0 - trajectory.tension)
        self.rotation_tangents = self._rotation_tangents()

    def _position_tangents(self, t: float) -> List[Vec]:
        """gz::math::Spline::RecalcTangents: Catmull-Rom, times ``t`` (1 - tension)."""
        p = self.positions
        n = len(p)
        if n < 2:
            return [(0.0, 0.0, 0.0)] * n
        closed = _equal(p[0], p[-1], 1e-3)      # Vector3d's operator== tolerance

        def half(a: Vec, b: Vec) -> Vec:
            return tuple((u - v) * 0.5 * t for u, v in zip(a, b))
        out = []
        for i in range(n):
            if i == 0:
                out.append(half(p[1], p[n - 2] if closed else p[0]))
            elif i == n - 1:
                out.append(out[0] if closed else half(p[i], p[i - 1]))
            else:
                out.append(half(p[i + 1], p[i - 1]))
        return out

    def _rotation_tangents(self) -> List[Quat]:
        """gz::math::RotationSpline::RecalcTangents (Shoemake)."""
        q = self.rotations
        n = len(q)
        if n < 2:
            return list(q)
        closed = _equal(q[0], q[-1], 1e-3)      # Quaterniond's operator== tolerance
        out = []
        for i in range(n):
            inv = _inverse(q[i])
            if i == 0:
                after, before = q[1], (q[n - 2] if closed else q[i])
            elif i == n - 1:
                after, before = (q[1] if closed else q[i]), q[i - 1]
            else:
                after, before = q[i + 1], q[i - 1]
            pre = _scaled(_added(_log(_mul(inv, after)), _log(_mul(inv, before))), -0.25)
            out.append(_mul(q[i], _exp(pre)))
        return out

    def _segment(self, time: float) -> Tuple[int, float]:
        """(index of the key frame before ``time``, fraction to the next): Animation::
        GetKeyFramesAtTime."""
        times = self.times
        while time > self.length > 0.0:
            time -= self.length
        index = next((i for i, t in enumerate(times) if t >= time), None)
        if index is None:                  # after the last: towards the first, a length later
            index, t2 = len(times) - 1, self.length + times[0]
        else:
            t2 = times[index]
            if index > 0 and time < times[index]:
                index -= 1
        t1 = times[index]
        return index, (0.0 if abs(t1 - t2) <= _EPS else (time - t1) / (t2 - t1))

    def at(self, time: float) -> Pose:
        """The pose ``time`` s after the trajectory's start (held within 0..its length, as
        Animation::SetTime holds a trajectory that does not loop)."""
        time = min(max(time, 0.0), self.length)
        index, t = self._segment(time)
        position, rotation = self.positions[index], self.rotations[index]
        if abs(t) > _EPS and index + 1 < len(self.times):
            if abs(t - 1.0) <= _EPS:
                position, rotation = self.positions[index + 1], self.rotations[index + 1]
            else:
                position = self._hermite(index, t)
                rotation = _squad(t, rotation, self.rotation_tangents[index],
                                  self.rotation_tangents[index + 1], self.rotations[index + 1])
        w, x, y, z = rotation
        return tuple(position), (x, y, z, w)

    def _hermite(self, i: int, t: float) -> Vec:
        p0, p1 = self.positions[i], self.positions[i + 1]
        m0, m1 = self.tangents[i], self.tangents[i + 1]
        t2, t3 = t * t, t * t * t
        h00, h10 = 2 * t3 - 3 * t2 + 1, t3 - 2 * t2 + t
        h01, h11 = -2 * t3 + 3 * t2, t3 - t2
        return tuple(h00 * a + h10 * b + h01 * c + h11 * d
                     for a, b, c, d in zip(p0, m0, p1, m1))


# --- the script, played in sim time ----------------------------------------------------------

class ActorMotion:
    """Plays one actor's script on its model (a world_models.WorldModel): Actor::Init, Play,
    Update and Reset."""

    def __init__(self, actor: Actor, model, time_ns: int = 0):
        self.actor = actor
        self.model = model
        # trajectories[id] is the last trajectory of that id, as Gazebo's map keeps it
        self.curves: Dict[int, PoseCurve] = {t.id: PoseCurve(t) for t in actor.trajectories
                                             if t.waypoints}
        self.spans: List[Tuple[int, float, float]] = []   # (id, start, end) s in the script
        start = 0.0
        for trajectory in actor.trajectories:
            self.spans.append((trajectory.id, start, start + trajectory.duration))
            start += trajectory.duration
        self.length = start
        self.restart(time_ns)

    def restart(self, time_ns: int) -> None:
        """Actor::Reset and Init: the script from its beginning at ``time_ns``; the actor
        back at its <pose> until its first frame."""
        self.active = self.actor.auto_start
        self.play_start = time_ns / 1e9
        self.previous_frame = time_ns / 1e9
        self.frames = 0

    def update(self, time_ns: int) -> Optional[Pose]:
        """Actor::Update at sim time ``time_ns``: the model at the script's pose when a frame
        is due; the pose set, or None."""
        if not self.active or not self.curves or not self.model.parts:
            return None
        now = time_ns / 1e9
        if now - self.previous_frame < FRAME_PERIOD_S:
            return None
        script = now - self.actor.delay_start - self.play_start
        if script < 0:
            return None
        if script >= self.length:
            if not self.actor.loop:
                self.active = False
                return None
            script -= self.length
            self.play_start = now
        span = next((s for s in self.spans if s[1] <= script <= s[2]), None)
        if span is None:
            return None
        self.previous_frame = now
        curve = self.curves.get(span[0])
        pose = curve.at(script - span[1]) if curve is not None else rf.IDENTITY
        self.model.set_state(pose, rf.ZERO_TWIST)
        self.frames += 1
        return pose


def actor_motions(world: World, models, time_ns: int = 0) -> List[ActorMotion]:
    """An ActorMotion for each actor of ``world`` whose model is in ``models`` (the
    world_models.ModelRegistry the world's models were added to)."""
    return [ActorMotion(actor, models.get(actor.name), time_ns)
            for actor in world.actors if actor.name in models]
