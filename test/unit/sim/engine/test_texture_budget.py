"""The texture budget of a pybullet client (texture_budget): which images are halved, how many
times, and the one line that says so. Pure arithmetic: no pybullet call (a Client that was
never connected will do). No ROS master."""
import pytest

from tutorial_turtlebot.sim.engine import texture_budget
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.engine.texture_budget import TextureUse, halved_images, plan

CID = Client(-4321)     # never connected: texture_budget keeps its state on it


@pytest.fixture(autouse=True)
def fresh_client():
    texture_budget.forget(CID)
    yield
    texture_budget.forget(CID)


def test_a_set_within_the_budget_is_drawn_as_it_is():
    uses = {"a": TextureUse("a.png", 64, 64), "b": TextureUse("b.png", 32, 16)}
    assert plan(CID, uses, per_visual=False, budget=64 * 64 + 32 * 16) is None
    assert halved_images(CID) == {"a": (64, 64), "b": (32, 16)}


def test_the_largest_is_halved_first_until_the_set_fits():
    uses = {"wall": TextureUse("walls/wall.png", 1024, 512),
            "poster": TextureUse("poster.jpg", 256, 256), "cup": TextureUse("cup.png", 32, 32)}
    line = plan(CID, uses, per_visual=False, budget=60_000)
    # 524,288 + 65,536 + 1,024 px: the wall twice (to 32,768), then the poster is the largest:
    # once, and the set fits: 32,768 + 16,384 + 1,024 = 50,176
    assert halved_images(CID) == {"wall": (256, 128), "poster": (128, 128), "cup": (32, 32)}
    assert line == ("texture budget of 60000 px: 2 of 3 texture images halved to fit (the "
                    "largest, wall.png, 1024 x 512 -> 256 x 128 px; doc/worlds.md)")


def test_an_image_counts_once_with_egl_and_per_visual_with_tinyrenderer():
    """One 64 x 64 image on three visuals: EGL draws all three with one texture (4,096 px);
    TinyRenderer keeps a copy per visual (three times that)."""
    uses = {"same": TextureUse("tex.png", 64, 64, visuals=3)}
    assert plan(CID, uses, per_visual=False, budget=5000) is None
    assert halved_images(CID) == {"same": (64, 64)}
    texture_budget.forget(CID)
    assert "1 of 1 texture images halved" in plan(CID, uses, per_visual=True, budget=5000)
    assert halved_images(CID) == {"same": (32, 32)}                   # 3 x 1,024 px


def test_later_images_fit_what_is_left_and_the_drawn_keep_their_size():
    plan(CID, {"a": TextureUse("a.png", 64, 64)}, per_visual=False, budget=5000)
    assert texture_budget.halvings(CID, "a", TextureUse("a.png", 64, 64), False) == 0
    plan(CID, {"a": TextureUse("a.png", 64, 64), "b": TextureUse("b.png", 64, 64)},
         per_visual=False, budget=5000)
    assert halved_images(CID) == {"a": (64, 64), "b": (16, 16)}      # 4,096 + 256 px


def test_never_dropped_and_never_below_the_smallest_side():
    uses = {str(i): TextureUse("%d.png" % i, 4096, 4096) for i in range(3)}
    line = plan(CID, uses, per_visual=False, budget=100)
    assert set(halved_images(CID).values()) == {(8, 8)}               # 3 x 64 px > 100: kept
    assert line.startswith("texture budget of 100 px passed: 192 px") and len(line) <= 200


def test_an_image_no_plan_took_is_planned_alone():
    use = TextureUse("late.png", 128, 128)
    assert texture_budget.halvings(CID, "late", use, False) == 0       # the default budget
