"""Work-arounds for rospy internals that the /gazebo node needs and rospy does not give: each
module replaces one rospy behaviour, named in its docstring's "Replaces" line, and touches
nothing of the node's own logic."""
