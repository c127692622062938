"""Where the /gazebo node's loop spends its time, part by part (``make bench`` shows it).

The loop thread is always in exactly one part; ``switch(part)`` ends the current one and
starts ``part``, so the parts add up to the loop's wall time with nothing counted twice:
  physics      stepping (the drive's control ticks, pybullet, the schedules)
  sensors      what the robots measure: laser rays, IMU, odometry, wheels, camera frames
  building     genpy messages filled field by field (model states, camera images, ...)
  serializing  bytes made: kept messages rewritten in place, genpy serialization
  sending      socket writes to the subscribers
  idle         sleeping until a moment is due (real time only)
  other        the rest: requests, pacing, the loop itself
A switch costs about 0.2 us. With TUTORIAL_TURTLEBOT_PART_TIMES=<file> in its environment the
node writes the totals there once a wall second, as one line ``sim_s part=s part=s ...``.
"""
import os
from time import perf_counter

PARTS = ("physics", "sensors", "building", "serializing", "sending", "idle", "other")
ENVIRONMENT_VARIABLE = "TUTORIAL_TURTLEBOT_PART_TIMES"


class PartTimes:
    """Seconds of the loop thread's wall time by part, since the start."""

    def __init__(self):
        self.totals = dict.fromkeys(PARTS, 0.0)
        self.part = "other"
        self._since = perf_counter()

    def switch(self, part: str) -> str:
        """End the current part now and start ``part``; the part that was running."""
        now = perf_counter()
        previous = self.part
        self.totals[previous] += now - self._since
        self.part, self._since = part, now
        return previous

    def run(self, part: str, action, *args):
        """``action(*args)`` counted in ``part``; the part before it runs on afterwards."""
        previous = self.switch(part)
        try:
            return action(*args)
        finally:
            self.switch(previous)

    def line(self, sim_time: float) -> str:
        """``sim_s part=seconds ...`` of everything so far (the running part included)."""
        totals = dict(self.totals)
        totals[self.part] += perf_counter() - self._since
        return "%.6f %s\n" % (sim_time, " ".join("%s=%.6f" % (p, totals[p]) for p in PARTS))


def read_line(line: str):
    """(sim seconds, {part: seconds}) of one ``line()``."""
    sim, *fields = line.split()
    return float(sim), {k: float(v) for k, v in (f.split("=") for f in fields)}


TIMES = PartTimes()


def report_path():
    """The file named by TUTORIAL_TURTLEBOT_PART_TIMES, or None."""
    return os.environ.get(ENVIRONMENT_VARIABLE) or None
