"""The texture budget of a pybullet client: how many times each texture image of its visuals is
halved so that the images it holds fit MAX_TEXTURE_PIXELS. No texture is ever dropped.

The rule (doc/worlds.md, "The texture budget"): each distinct image (by the sha256 of its
file) counts once, width x height px as drawn; with TinyRenderer (no EGL), which keeps a
decoded copy of a texture for every visual that uses it, it counts once per such visual. When a
world's images pass the budget, the largest of them (by what they count) is halved, each side
rounded up, again and again until the set fits or every image is down to
texture_images.MIN_HALVED_SIDE px a side. Images of models spawned later are halved the same way
to fit what is left; the images already drawn keep their size.

Units: pixels. State is kept on the client (``Client.texture_plan``) until ``forget``
(rendering.disable_egl calls it).
"""
import heapq
import os
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from ..files.meshes.texture_images import MIN_HALVED_SIDE, halved_size
from .client import Client

# px: 64 M px of images (about 256 MB as decoded RGBA, a third more with their mipmaps).
MAX_TEXTURE_PIXELS = 64 * 1024 * 1024


@dataclass
class TextureUse:
    """One texture image as a world's visuals use it."""

    name: str          # its file, for the log line
    width: int         # px, as the file has it
    height: int        # px
    visuals: int = 1   # visuals drawn with it

    def pixels(self, halvings: int) -> int:
        width, height = halved_size(self.width, self.height, halvings)
        return width * height


@dataclass
class _Client:
    per_visual: bool                                         # TinyRenderer: copies per visual
    uses: Dict[str, TextureUse] = field(default_factory=dict)    # digest -> use
    halvings: Dict[str, int] = field(default_factory=dict)       # digest -> times halved

    def cost(self, digest: str, halvings: Optional[int] = None) -> int:
        use = self.uses[digest]
        pixels = use.pixels(self.halvings[digest] if halvings is None else halvings)
        return pixels * (use.visuals if self.per_visual else 1)


def plan(client: Client, uses: Dict[str, TextureUse], per_visual: bool,
         budget: Optional[int] = None) -> Optional[str]:
    """Take the texture images ``uses`` (sha256 -> use) of new visuals of ``client``
    and decide how many times each new image is halved (``halvings`` answers); ``per_visual``:
    the client's renderer keeps a copy per visual (TinyRenderer). ``budget``: px, default
    MAX_TEXTURE_PIXELS. Returns one line (at most 200 characters) when an image was halved or
    the budget could not be met; else None."""
    budget = MAX_TEXTURE_PIXELS if budget is None else budget
    state = client.texture_plan
    if state is None:
        state = client.texture_plan = _Client(per_visual)
    new: List[str] = []
    for digest, use in uses.items():
        if digest in state.uses:
            state.uses[digest].visuals += use.visuals
        else:
            state.uses[digest] = TextureUse(use.name, use.width, use.height, use.visuals)
            state.halvings[digest] = 0
            new.append(digest)
    total = sum(state.cost(d) for d in state.uses)
    heap = [(-state.cost(d), d) for d in new]
    heapq.heapify(heap)
    while total > budget and heap:
        _, digest = heapq.heappop(heap)
        now, halved = state.cost(digest), state.cost(digest, state.halvings[digest] + 1)
        if halved >= now:
            continue                        # down to the smallest side: no more halving
        state.halvings[digest] += 1
        total -= now - halved
        heapq.heappush(heap, (-halved, digest))
    shrunk = [d for d in new if state.halvings[d]]
    if total > budget:
        return ("texture budget of %s passed: %s of texture images, the new ones halved down "
                "to %d px a side (doc/worlds.md)"
                % (_pixels(budget), _pixels(total), MIN_HALVED_SIDE))
    if not shrunk:
        return None
    largest = max(shrunk, key=lambda d: state.uses[d].width * state.uses[d].height)
    use = state.uses[largest]
    return ("texture budget of %s: %d of %d texture images halved to fit (the largest, %s, "
            "%d x %d -> %d x %d px; doc/worlds.md)"
            % (_pixels(budget), len(shrunk), len(new), os.path.basename(use.name)[-40:],
               use.width, use.height,
               *halved_size(use.width, use.height, state.halvings[largest])))


def _pixels(count: int) -> str:
    """"64 Mpx" or "300 px"."""
    return "%.0f Mpx" % (count / 2 ** 20) if count >= 2 ** 20 else "%d px" % count


def halvings(client: Client, digest: str, use: TextureUse, per_visual: bool) -> int:
    """How many times the image of sha256 ``digest`` is halved in ``client``; an image no
    ``plan`` took yet is planned alone, with ``use``."""
    state = client.texture_plan
    if state is None or digest not in state.halvings:
        plan(client, {digest: use}, per_visual)
        state = client.texture_plan
    return state.halvings[digest]


def halved_images(client: Client) -> Dict[str, Tuple[int, int]]:
    """{sha256: (width, height) px as drawn} of the images of ``client``."""
    state = client.texture_plan
    if state is None:
        return {}
    return {d: halved_size(u.width, u.height, state.halvings[d]) for d, u in state.uses.items()}


def forget(client: Client) -> None:
    """Forget the textures of ``client``."""
    client.texture_plan = None
