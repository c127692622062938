"""The keyboard teleop's key-to-twist state machine (doc/turtlebot3.md 5.1), with no terminal code.

Call :meth:`Teleop.step` once per loop with the key read (None when the 0.1 s read timed out);
it returns the (ramped) command to publish: linear m/s along +x, angular rad/s counter-clockwise.
"""
from typing import NamedTuple, Optional

# Key -> (x, th): direction of travel and of turn, scaled by speed and turn.
MOVE_KEYS = {
    "u": (1, 1), "i": (1, 0), "o": (1, -1),
    "j": (0, 1), "l": (0, -1),
    "m": (-1, -1), ",": (-1, 0), ".": (-1, 1),
}

# Key -> (factor on speed, factor on turn).
SPEED_KEYS = {
    "q": (1.1, 1.1), "z": (0.9, 0.9),
    "w": (1.1, 1.0), "x": (0.9, 1.0),
    "e": (1.0, 1.1), "c": (1.0, 0.9),
}

STOP_KEYS = (" ", "k")

IDLE_LOOPS = 4        # more idle loops than this (other keys or timeouts) stop smoothly
LINEAR_STEP = 0.02    # m/s, largest change of the output per loop
ANGULAR_STEP = 0.1    # rad/s, largest change of the output per loop
BANNER_EVERY = 15     # the banner is printed again after this many status lines

BANNER = """
Control Your TurtleBot3!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%
space key, k : force stop
anything else : stop smoothly

CTRL-C to quit
"""


class Output(NamedTuple):
    """What one loop publishes and prints."""

    linear: float          # m/s
    angular: float         # rad/s
    text: Optional[str]    # lines to print, or None


def _approach(value: float, target: float, step: float) -> float:
    """``value`` moved toward ``target`` by at most ``step``."""
    return min(target, value + step) if target > value else max(target, value - step)


def _clamp(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))


class Teleop:
    """State of the keyboard teleop for a robot limited to ``max_linear`` m/s and
    ``max_angular`` rad/s; ``model`` only names the robot in the banner, and so does ``topic``
    (the resolved cmd_vel) where it is not plain /cmd_vel: with one terminal per robot, the
    first line of each says which robot it drives."""

    def __init__(self, max_linear: float, max_angular: float, model: str = "burger",
                 speed: float = 0.2, turn: float = 1.0, topic: str = "/cmd_vel"):
        self.max_linear = max_linear
        self.max_angular = max_angular
        self.model = model
        self.topic = topic
        self.speed = min(speed, max_linear)   # m/s for a full x
        self.turn = min(turn, max_angular)    # rad/s for a full th
        self.x = 0
        self.th = 0
        self.linear = 0.0    # m/s, the output
        self.angular = 0.0   # rad/s, the output
        self.idle = 0        # loops since the last movement or speed key
        self.status_count = 0

    def banner(self) -> str:
        """The handout's banner, with this robot's limits (and its topic, see the class)."""
        banner = BANNER
        if self.topic != "/cmd_vel":
            banner = banner.replace("TurtleBot3!\n", "TurtleBot3! (driving %s)\n" % self.topic, 1)
        return banner + "%s: speed up to %g m/s, turn up to %g rad/s\n" % (
            self.model, self.max_linear, self.max_angular)

    def status(self) -> str:
        """The status line, e.g. "currently:\\tspeed 0.2\\tturn 1" (3 significant digits:
        five presses of q give turn 1.61, not 1.61051)."""
        return "currently:\tspeed %.3g\tturn %.3g" % (self.speed, self.turn)

    def step(self, key: Optional[str]) -> Output:
        """One loop: apply ``key`` (None for a read timeout), ramp the output, return it."""
        text = None
        if key in MOVE_KEYS:
            self.x, self.th = MOVE_KEYS[key]
            self.idle = 0
        elif key in SPEED_KEYS:
            text = self._scale(*SPEED_KEYS[key])
            self.idle = 0
        elif key in STOP_KEYS:
            self.x = self.th = 0
            self.linear = self.angular = 0.0
        else:
            self.idle += 1
            if self.idle > IDLE_LOOPS:
                self.x = self.th = 0
        self.linear = _clamp(_approach(self.linear, self.speed * self.x, LINEAR_STEP),
                             self.max_linear)
        self.angular = _clamp(_approach(self.angular, self.turn * self.th, ANGULAR_STEP),
                              self.max_angular)
        return Output(self.linear, self.angular, text)

    def _scale(self, speed_factor: float, turn_factor: float) -> str:
        """Scale speed and turn within the limits; the status text to print."""
        self.speed = min(self.speed * speed_factor, self.max_linear)
        self.turn = min(self.turn * turn_factor, self.max_angular)
        lines = []
        if self.status_count == BANNER_EVERY - 1:
            lines.append(self.banner())
        self.status_count = (self.status_count + 1) % BANNER_EVERY
        lines.append(self.status())
        if (speed_factor > 1.0 and self.speed == self.max_linear) or \
                (turn_factor > 1.0 and self.turn == self.max_angular):
            lines.append("(%s limits: %g m/s, %g rad/s)"
                         % (self.model, self.max_linear, self.max_angular))
        return "\n".join(lines)
