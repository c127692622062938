"""What every node of the package does with its standard output: lines leave as they are said."""
import sys


def line_buffered() -> None:
    """Make stdout line-buffered. rospy writes its log lines (loginfo, logwarn) to stdout and
    never flushes: into roslaunch's log file or a pipe they would arrive kilobytes late, unless
    PYTHONUNBUFFERED happens to be set (it is not on a Debian 13 desktop)."""
    reconfigure = getattr(sys.stdout, "reconfigure", None)
    if reconfigure is not None:
        reconfigure(line_buffering=True)
