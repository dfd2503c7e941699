"""Destructible terrain: blasts carve craters out of a static landscape and throw the crates on it.

Every half second a blast (World.explode, the viewer's right click) lands beside a crate; the terrain's mass and
outline follow at once, and the crates fall into the craters.
Run: python terrain.py (right click to blast more), or python terrain.py --frames 120 --screenshot terrain.png
"""
from typing import List, Optional, Tuple

import numpy as np

import common
from physpix import World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
# Blasts: (frame, world point). Each lands just under a crate.
BLASTS = [(20, (180.0, 220.0)), (50, (330.0, 222.0)), (80, (470.0, 216.0))]


def landscape() -> np.ndarray:
    """Rolling hills as wide as the view, from y = 160 down: solid below a sine curve."""
    top = 215 + 14 * np.sin(np.arange(WIDTH) / 45.0)
    return (np.arange(160, HEIGHT)[:, None] >= top[None, :]).astype(np.uint8)


class Terrain(Viewer):
    """The scene in the viewer, with timed blasts that count the pixels they take."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        ground = common.sprite(landscape(), (122, 86, 52), edge=(70, 150, 60), border=4)  # dirt under grass
        self.terrain = world.create_body(rgba=ground, type="static", position=(WIDTH / 2, (160 + HEIGHT) / 2))
        box = common.sprite(np.ones((24, 24)), (214, 150, 70), edge=(120, 80, 40))
        self.crates = [world.create_body(rgba=box, position=(x, 160.0)) for x in (180, 330, 470)]
        super().__init__(world, size)
        self.erased = 0  # pixels the blasts took from every body, as the library counted them
        self.pending: List[Tuple[int, Tuple[float, float]]] = list(BLASTS)

    def step(self) -> None:
        while self.pending and self.pending[0][0] <= self.frame_index:
            self.erased += self.blast(self.pending.pop(0)[1], radius=28)
        super().step()


def main(argv=None):
    return common.main(Terrain, __doc__, argv)


if __name__ == "__main__":
    main()
