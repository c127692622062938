"""How things look: SDF materials, Gazebo's named materials, OGRE material scripts."""
