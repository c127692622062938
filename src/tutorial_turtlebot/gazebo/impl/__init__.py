"""Work-arounds for rospy internals that the /gazebo node needs and rospy does not give: each
module replaces one rospy behaviour, named in its docstring's "Replaces" line, and touches
nothing of the node's own logic. impl/ imports nothing of the package outside itself: what the
node wants of it (timing the writes) it passes in (test_wings.py checks)."""
