"""gazebo/send_queue.py: paced, a step's messages are made at once and written when their wall
time comes; as fast as possible they are gathered and written once a SEND_GAP, what clients
wait for (a scan, a camera frame) at once."""
import time

from tutorial_turtlebot.gazebo.send_queue import SEND_GAP, SendQueue


class Connection:
    done = False

    def __init__(self):
        self.writes = []

    def write_data(self, data):
        self.writes.append(data)


def publisher(sends, connection, data=b"m"):
    """A publish(due) that writes one message per due output, as the node's publishers do."""
    def publish(due):
        for _ in due:
            sends.held.append((connection, data))
    return publish


def test_kept_messages_leave_when_due_in_one_write():
    sends, connection = SendQueue(), Connection()
    now = time.monotonic()
    sends.keep(publisher(sends, connection), [(None, "clock"), (None, "imu")], now + 0.05)
    sends.send_due_now()
    assert connection.writes == []                  # not due yet
    assert sends.next_due() == now + 0.05
    time.sleep(0.06)
    sends.send_due_now()
    assert connection.writes == [b"mm"] and sends.next_due() is None


def test_nothing_due_makes_nothing_kept():
    sends = SendQueue()
    sends.keep(publisher(sends, Connection()), [], time.monotonic())
    assert sends.next_due() is None and sends.held is None


def test_as_fast_as_possible_messages_are_gathered_a_send_gap():
    sends, connection = SendQueue(), Connection()
    publish = publisher(sends, connection)
    sends.send_gathered(publish, [(None, "imu")])    # the first goes at once
    sends.send_gathered(publish, [(None, "imu")])    # within the gap: kept
    sends.send_gathered(publish, [(None, "odom")])
    assert connection.writes == [b"m"]
    time.sleep(SEND_GAP + 0.001)
    sends.send_gathered(publish, [])                 # the gap passed: the rest in one write
    assert connection.writes == [b"m", b"mm"]


def test_a_scan_leaves_at_once_with_everything_before_it():
    sends, connection = SendQueue(), Connection()
    publish = publisher(sends, connection)
    sends.send_gathered(publish, [(None, "imu")])
    sends.send_gathered(publish, [(None, "odom")])
    robot = object()
    sends.send_gathered(publish, [(robot, "scan")])  # within the gap, but a client waits for it
    assert connection.writes == [b"m", b"mm"]


def test_the_backlogs_writes_are_the_loops_sending_time():
    """The publishers' connections write through sends.backlog, timed as part_times' "sending"
    (what make bench shows)."""
    from tutorial_turtlebot.gazebo.part_times import TIMES
    sends, parts = SendQueue(), []
    assert sends.backlog.timed(lambda data: parts.append(TIMES.part) or True, b"m") is True
    assert parts == ["sending"] and TIMES.part != "sending"
