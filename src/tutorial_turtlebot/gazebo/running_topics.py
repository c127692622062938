"""The topics of what runs in the simulation beside the robots, kept in step with it: the world
models' sensors (world_sensor_topics) and every model's plugins (model_plugin_topics) each hold
one ``RunningTopics``. A new item (a spawned model's sensor or plugin) gets its topic, a gone
one's is taken back, and one item's failure is logged (once a period) and skipped without
ending the node."""
import math
import time

import rospy

from ..errors import one_line

OUTPUT_ERROR_PERIOD = 10.0   # wall s between two error lines of one item


class RunningTopics:
    """item -> its topic (an object with ``publish(stamp)`` and ``close()``), made by
    ``make_topic(item)``; ``kind`` names an item in the log ("world sensor", "model plugin")."""

    def __init__(self, kind: str, make_topic):
        self.kind = kind
        self.make_topic = make_topic
        self.topics = {}
        self._generation = None
        self._errors = {}            # item name -> wall time its next error may be logged

    def sync(self, generation, items) -> None:
        """Follow the running ``items`` (their ``generation`` changes with them): a topic for
        each new one, the topics of those gone taken back."""
        if generation == self._generation:
            return
        running = set(items)
        for item in [i for i in self.topics if i not in running]:
            self.topics.pop(item).close()
        for item in items:
            if item not in self.topics:
                try:
                    self.topics[item] = self.make_topic(item)
                except Exception as err:  # noqa: BLE001 - one item must not end the node
                    self.failed(item.name, err)
        self._generation = generation

    def publish(self, due, stamp) -> None:
        """The messages of the ``due`` items, stamped ``stamp``."""
        for item in due:
            topic = self.topics.get(item)
            if topic is None:
                continue
            try:
                topic.publish(stamp)
            except Exception as err:  # noqa: BLE001 - one item must not end the node
                self.failed(item.name, err)

    def close(self) -> None:
        for topic in self.topics.values():
            topic.close()
        self.topics.clear()

    def failed(self, name: str, err: Exception) -> None:
        """Log that item ``name`` failed (at most once an OUTPUT_ERROR_PERIOD) and go on."""
        now = time.monotonic()
        if now < self._errors.get(name, -math.inf):
            return
        self._errors[name] = now + OUTPUT_ERROR_PERIOD
        rospy.logerr("gazebo: %s %s failed and was skipped: %s", self.kind, name, one_line(err))
