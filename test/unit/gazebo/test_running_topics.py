"""RunningTopics: the topics of the world's sensors and plugins follow what runs (a new item
gets one, a gone one's is closed), and one item's failure, making or publishing, is skipped
without stopping the others."""
from collections import namedtuple

from tutorial_turtlebot.gazebo.running_topics import RunningTopics

Item = namedtuple("Item", "name")


class Topic:
    def __init__(self, item, log):
        self.item, self.log = item, log

    def publish(self, stamp):
        if self.item.name == "broken":
            raise ValueError("no reading")
        self.log.append((self.item.name, stamp))

    def close(self):
        self.log.append((self.item.name, "closed"))


def test_follows_the_running_items_and_skips_a_failure():
    log = []

    def make(item):
        if item.name == "unmakeable":
            raise RuntimeError("bad topic")
        return Topic(item, log)

    topics = RunningTopics("world sensor", make)
    a, b, broken, unmakeable = (Item(n) for n in ("a", "b", "broken", "unmakeable"))
    topics.sync(1, [a, broken, unmakeable])
    assert set(topics.topics) == {a, broken}
    topics.publish([a, broken, unmakeable], 5)
    assert log == [("a", 5)]                       # the broken one skipped, the rest went on
    topics.sync(1, [b])                            # same generation: nothing changes
    assert set(topics.topics) == {a, broken}
    topics.sync(2, [b])
    assert set(topics.topics) == {b} and ("a", "closed") in log
    topics.close()
    assert topics.topics == {} and ("b", "closed") in log
