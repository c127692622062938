"""make corpus: the pure part of bench/corpus.py and bench/corpus_probe.py (numpy, no ROS).

What a camera image shows, what a scan sees, whether a drive went as commanded, what a
roslaunch log says when the sim refused a world, and the markdown table. Units: metres,
radians, seconds, 0..255 colour channels.
"""
import math
import re

import numpy as np

LEVELS = 8            # levels per colour channel when counting distinct colours (512 colours)
MIN_SHARE = 0.002     # a quantized colour counts when it covers this share of an image
CHROMA = 24           # a pixel is coloured when its channels differ by this much (0..255)
COLOURED = 0.01       # an image is "colour" when this share of its pixels is coloured
DRIVE_TOLERANCE = 0.2     # the drive test passes within this share of the commanded motion
LATERAL_TOLERANCE = 0.05  # m sideways at most while driving straight
PYTHON_ERROR = re.compile(r"^[\w.]+(Error|Exception|Interrupt|Exit): ")
ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]|\x1b\][^\x07]*\x07")


def quantized_colours(image, levels=LEVELS, min_share=MIN_SHARE):
    """The set of colours (r, g, b levels) that each cover at least ``min_share`` of an
    H x W x 3 uint8 ``image``, each channel cut into ``levels`` levels."""
    pixels = np.asarray(image, dtype=np.uint8).reshape(-1, 3).astype(np.int64)
    step = 256 // levels
    codes = (pixels[:, 0] // step) * levels * levels + (pixels[:, 1] // step) * levels \
        + pixels[:, 2] // step
    counts = np.bincount(codes, minlength=levels ** 3)
    keep = np.nonzero(counts >= max(1, min_share * len(pixels)))[0]
    return {(int(c) // (levels * levels), (int(c) // levels) % levels, int(c) % levels)
            for c in keep}


def chroma_share(image, threshold=CHROMA):
    """Share of an image's pixels whose largest and smallest channel differ by ``threshold``."""
    pixels = np.asarray(image, dtype=np.int16).reshape(-1, 3)
    return float(np.mean(pixels.max(axis=1) - pixels.min(axis=1) >= threshold))


def camera_summary(images):
    """(distinct quantized colours over all ``images``, whether any image is in colour)."""
    colours = set()
    for image in images:
        colours |= quantized_colours(image)
    return len(colours), any(chroma_share(image) >= COLOURED for image in images)


def finite_share(ranges):
    """Share of a scan's ranges that are returns (finite), 0..1."""
    ranges = np.asarray(ranges, dtype=float)
    return float(np.mean(np.isfinite(ranges))) if ranges.size else 0.0


def wrap(angle):
    """``angle`` (rad) into -pi..pi."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def drive_result(start, after_line, after_turn, distance, turn):
    """The drive test from poses (x, y, yaw): ``start``; ``after_line``, after a straight
    drive commanded to go ``distance`` m; ``after_turn``, after a turn commanded to turn
    ``turn`` rad. A dict: forward and lateral m, turned rad, ok (all within tolerance)."""
    dx, dy = after_line[0] - start[0], after_line[1] - start[1]
    forward = dx * math.cos(start[2]) + dy * math.sin(start[2])
    lateral = -dx * math.sin(start[2]) + dy * math.cos(start[2])
    turned = wrap(after_turn[2] - after_line[2])
    ok = (abs(forward - distance) <= DRIVE_TOLERANCE * distance
          and abs(lateral) <= LATERAL_TOLERANCE
          and abs(turned - turn) <= DRIVE_TOLERANCE * abs(turn))
    return {"forward": round(forward, 3), "lateral": round(lateral, 3),
            "turned": round(turned, 3), "distance": distance, "turn": turn, "ok": ok}


def refusal_line(log_text):
    """The sim's one-line refusal in a roslaunch log (its [FATAL] line without the stamp and
    node name), else the last line of a Python traceback in it ("crash: ..."), or None."""
    lines = ANSI.sub("", log_text).splitlines()
    for line in reversed(lines):
        if "[FATAL]" in line:
            text = line.split("]: ", 1)[-1].strip()
            return text[len("gazebo: "):] if text.startswith("gazebo: ") else text
    for line in reversed(lines):
        if PYTHON_ERROR.match(line):
            return "crash: " + line.strip()
    return None


def warning_lines(log_text):
    """The sim's [WARN] lines in a roslaunch log, without stamps, in order."""
    return [line.split("]: ", 1)[-1].strip() for line in ANSI.sub("", log_text).splitlines()
            if line.startswith("[WARN]")]


def short(text, width=90):
    """``text`` on one line of at most ``width`` characters."""
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[:width - 3] + "..."


def _cell(row, key, fmt):
    value = row.get(key)
    return "-" if value is None else fmt(value)


def table_rows(results, reference):
    """Markdown rows (strings) of the corpus table: one per world result (dicts as
    bench/corpus.py writes them), CPU as ratios to ``reference``'s (turtlebot3_world)."""
    lines = ["| world | loaded | models | laser | camera colours | drive | start cold / warm s "
             "| CPU per sim s, x turtlebot3_world (camera on) |",
             "|---|---|---|---|---|---|---|---|"]
    ref_cpu, ref_cam = reference.get("cpu"), reference.get("cpu_camera")
    for row in results:
        loaded = "yes" if row.get("loaded") else "**no**"
        if row.get("workaround"):
            loaded += "; measured with " + row["workaround"]
        colours = _cell(row, "colours", lambda c: "%d, %s" % (
            c, "colour" if row.get("in_colour") else "grey"))
        drive = _cell(row, "drive", lambda d: "ok" if d["ok"] else "%.2f of %.2f m, %.2f of "
                      "%.2f rad" % (d["forward"], d["distance"], d["turned"], d["turn"]))
        start = "%s / %s" % (_cell(row, "cold_s", "{:.1f}".format),
                             _cell(row, "warm_s", "{:.1f}".format))
        cpu = "-"
        if row.get("cpu") is not None and ref_cpu:
            cpu = "%.2fx" % (row["cpu"] / ref_cpu)
            if row.get("cpu_camera") is not None and ref_cam:
                cpu += " (%.2fx)" % (row["cpu_camera"] / ref_cam)
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            row["name"], loaded, _cell(row, "models", str),
            _cell(row, "laser", lambda s: "%d %%" % round(100 * s)), colours, drive, start, cpu))
    return lines


def format_report(results, reference, header=""):
    """The whole markdown report: ``header``, the reference line, the table, and one line
    per world that did not load unmodified (its one-line reason)."""
    lines = [header] if header else []
    if reference:
        lines.append("Reference, built-in turtlebot3_world (Waffle Pi at its spawn): start %s s "
                     "warm; %s CPU s per sim s, %s with the camera subscribed; camera %s."
                     % (_cell(reference, "warm_s", "{:.1f}".format),
                        _cell(reference, "cpu", "{:.3f}".format),
                        _cell(reference, "cpu_camera", "{:.3f}".format),
                        _cell(reference, "colours", lambda c: "%d colours" % c)))
        lines.append("")
    lines += table_rows(results, reference)
    failed = [row for row in results if not row.get("loaded") or row.get("reason")]
    if failed:
        lines += ["", "Why not (one line each):", ""]
        lines += ["- %s: `%s`" % (row["name"], short(row.get("reason", "?"), 300).replace("`", "'"))
                  for row in failed]
    loaded = sum(1 for row in results if row.get("loaded") and not row.get("workaround"))
    lines += ["", "%d of %d worlds loaded unmodified." % (loaded, len(results))]
    return "\n".join(lines) + "\n"
