"""The colours of Gazebo 11's own ``Gazebo/<Name>`` materials (its ``gazebo.material`` script),
as a visual's ``<material><script><name>`` names them. Plain data: no ROS, no pybullet.

Colours are (r, g, b, a) in 0..1.
"""
from typing import Dict, FrozenSet

from ..world_types import Rgba

# The colour of each common Gazebo/<Name> material of Gazebo 11's gazebo.material: its diffuse
# colour; for a textured one the mean colour of its texture (approximate); a few whose look
# comes from their ambient term (SkyBlue) take that. Transparent and glowing ones are drawn
# opaque. A name not here is drawn grey (DEFAULT_RGBA).
GAZEBO_MATERIALS: Dict[str, Rgba] = {
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/Gray": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/DarkGray": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1, 1.0),
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/RedBright": (0.87, 0.26, 0.07, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/SkyBlue": (0.13, 0.44, 0.70, 1.0),
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/ZincYellow": (0.9725, 0.9529, 0.2078, 1.0),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
    "Gazebo/Indigo": (0.33, 0.0, 0.5, 1.0),
    "Gazebo/Gold": (0.8, 0.4974, 0.0071, 1.0),
    "Gazebo/Chrome": (0.7, 0.7, 0.72, 1.0),
    "Gazebo/WhiteGlow": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/RedGlow": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/GreenGlow": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/BlueGlow": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/YellowGlow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/PurpleGlow": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/TurquoiseGlow": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/BlueLaser": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/RedTransparent": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/GreenTransparent": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/BlueTransparent": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/YellowTransparent": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/OrangeTransparent": (1.0, 0.44, 0.0, 1.0),
    "Gazebo/GreyTransparent": (0.5, 0.5, 0.5, 1.0),
    "Gazebo/BlackTransparent": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/DarkMagentaTransparent": (0.6, 0.0, 0.6, 1.0),
    "Gazebo/Shadow": (0.2, 0.2, 0.2, 1.0),          # a see-through dark grey in Gazebo
    # textured: the mean colour of the texture
    "Gazebo/Wood": (0.62, 0.45, 0.28, 1.0),
    "Gazebo/WoodFloor": (0.55, 0.38, 0.22, 1.0),
    "Gazebo/WoodPallet": (0.66, 0.53, 0.37, 1.0),
    "Gazebo/LightWood": (0.80, 0.66, 0.47, 1.0),
    "Gazebo/Bricks": (0.58, 0.33, 0.26, 1.0),
    "Gazebo/CeilingTiled": (0.80, 0.80, 0.78, 1.0),
    "Gazebo/PaintedWall": (0.85, 0.83, 0.78, 1.0),
    "Gazebo/Rockwall": (0.45, 0.42, 0.38, 1.0),
    "Gazebo/Grass": (0.33, 0.47, 0.20, 1.0),
    "Gazebo/Leaf": (0.24, 0.40, 0.12, 1.0),
    "Gazebo/Trunk": (0.35, 0.35, 0.35, 1.0),         # the road texture of OSM trunk roads
    "Gazebo/Road": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/Asphalt": (0.30, 0.30, 0.30, 1.0),
    "Gazebo/Residential": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Tertiary": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Secondary": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Primary": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/Motorway": (0.33, 0.33, 0.33, 1.0),
    "Gazebo/Footway": (0.60, 0.58, 0.55, 1.0),
    "Gazebo/Pedestrian": (0.60, 0.58, 0.55, 1.0),
    "Gazebo/Lanes": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/CloudySky": (0.62, 0.70, 0.82, 1.0),
}

# The materials above that Gazebo draws with a texture (their colour: its mean). A <diffuse>
# given beside one tints that texture, so it multiplies the mean colour (sdf_looks).
GAZEBO_TEXTURED: FrozenSet[str] = frozenset((
    "Gazebo/Wood", "Gazebo/WoodFloor", "Gazebo/WoodPallet", "Gazebo/LightWood", "Gazebo/Bricks",
    "Gazebo/CeilingTiled", "Gazebo/PaintedWall", "Gazebo/Rockwall", "Gazebo/Grass",
    "Gazebo/Leaf", "Gazebo/Trunk", "Gazebo/Road", "Gazebo/Asphalt", "Gazebo/Residential",
    "Gazebo/Tertiary", "Gazebo/Secondary", "Gazebo/Primary", "Gazebo/Motorway", "Gazebo/Footway",
    "Gazebo/Pedestrian", "Gazebo/Lanes", "Gazebo/CloudySky"))
