"""The folders the unit tests read from, wherever a test file sits in test/unit's tree."""
import os

UNIT = os.path.dirname(os.path.abspath(__file__))     # test/unit
ROOT = os.path.dirname(os.path.dirname(UNIT))           # the repository
DATA = os.path.join(UNIT, "data")                       # test/unit/data
FIXTURES = os.path.join(ROOT, "test", "fixtures")      # test/fixtures
