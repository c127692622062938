#!/usr/bin/env python3
"""rostest node: the contact and IMU sensors of a world file's models through the real /gazebo
(world_contacts.test; the world is test/fixtures/world_contacts/world_contacts.world, no
robot). A 2 kg box resting on a static force plate: the plate's gazebo_ros_bumper publishes one
ContactState, plate against box, whose total force is the box's weight pushing down; the box's
gazebo_ros_imu_sensor reads +9.8 m/s^2 up and no rates; once the box is lifted away with
set_model_state (onto the ground beside it) the plate reports no contact. Every wait is on
wall time with a limit."""
import rospy
import rostest
from gazebo_msgs.msg import ContactsState, ModelState
from sensor_msgs.msg import Imu

from sim_test_support import WAIT, SimTestCase, pose, wait_for

WEIGHT = 2.0 * 9.8     # N


class WorldContactsTest(SimTestCase):
    def settled(self, topic, msg_type):
        """A message of ``topic`` after 1 s of sim time (the box has settled)."""
        wait_for(lambda: self.gz.clock.latest(WAIT).clock.to_sec() > 1.0, WAIT)
        msg = rospy.wait_for_message(topic, msg_type, WAIT)
        self.assertIsNotNone(msg)
        return msg

    def test_1_the_force_plate_feels_the_boxs_weight(self):
        msg = self.settled("/plate_contacts", ContactsState)
        self.assertEqual(msg.header.frame_id, "world")
        [state] = msg.states
        self.assertEqual((state.collision1_name, state.collision2_name),
                         ("force_plate::plate::top", "crate::body::shell"))
        self.assertAlmostEqual(state.total_wrench.force.z, -WEIGHT, delta=0.02 * WEIGHT)
        self.assertEqual(len(state.wrenches), len(state.contact_positions))
        self.assertAlmostEqual(state.contact_normals[0].z, -1.0, places=3)

    def test_2_the_boxs_imu_reads_gravitys_reaction(self):
        msg = self.settled("/crate/imu", Imu)
        self.assertEqual(msg.header.frame_id, "crate_imu_link")
        self.assertAlmostEqual(msg.linear_acceleration.z, 9.8, delta=0.05)
        for rate in (msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z):
            self.assertAlmostEqual(rate, 0.0, delta=1e-3)
        self.assertAlmostEqual(msg.orientation.w, 1.0, places=3)

    def test_3_no_contact_once_the_box_is_lifted_away(self):
        self.settled("/plate_contacts", ContactsState)
        # lifted off the plate and set down on the ground beside it, where it stays
        state = ModelState(model_name="crate", pose=pose(3.0, 3.0, 0.2),
                           reference_frame="world")
        self.assertTrue(self.gz.set_model_state(model_state=state).success)
        rospy.wait_for_message("/plate_contacts", ContactsState, WAIT)
        msg = rospy.wait_for_message("/plate_contacts", ContactsState, WAIT)
        self.assertEqual(msg.states, [])


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_world_contacts", WorldContactsTest)
