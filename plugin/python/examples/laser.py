"""A raycast laser that cuts terrain: World.raycast finds the first solid pixel along the beam, and each frame
erases a small circle there, so the beam burns a trench deeper on every sweep.

The emitter sweeps down and back up over the same angles; the second pass meets the ground farther along the
beam, where the first left off.
Run: python laser.py, or python laser.py --frames 160 --screenshot laser.png
"""
import math
from typing import List, Optional, Tuple

import numpy as np

import common
from physpix import World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
EMITTER = (60.0, 60.0)      # world px
REACH = 900.0               # the beam's length, px
SWEEP = (0.35, 0.75)        # radians below the horizontal, first and last
SWEEP_FRAMES = 40           # down in 40 frames, back up over the same angles in 40 more
BURN = 6.0                  # the radius erased where the beam meets the ground, px


def beam_angle(frame: int) -> float:
    """Down then back up: frames f and 2·SWEEP_FRAMES − 1 − f aim the same way."""
    k = frame % (2 * SWEEP_FRAMES)
    k = k if k < SWEEP_FRAMES else 2 * SWEEP_FRAMES - 1 - k
    return SWEEP[0] + (SWEEP[1] - SWEEP[0]) * k / (SWEEP_FRAMES - 1)


class Laser(Viewer):
    """The scene in the viewer; each step fires the beam and burns where it hits."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        ground = np.ones((HEIGHT - 200, WIDTH), np.uint8)
        self.terrain = world.create_body(rgba=common.sprite(ground, (96, 84, 72), edge=(70, 150, 60), border=4),
                                         type="static", position=(WIDTH / 2, (200 + HEIGHT) / 2))
        box = common.sprite(np.ones((20, 20)), (214, 150, 70), edge=(120, 80, 40))
        for x in (330, 560):
            world.create_body(rgba=box, position=(float(x), 189.0))
        self.emitter = world.create_body(rgba=common.sprite(np.ones((16, 16)), (200, 40, 40)), type="static",
                                         position=(EMITTER[0] - 10, EMITTER[1]))
        super().__init__(world, size)
        self.beam: Tuple[Tuple[float, float], Tuple[float, float]] = (EMITTER, EMITTER)
        self.hits: List[Tuple[int, float]] = []  # (frame, fraction along the beam) of each hit on the terrain
        self.erased = 0                          # terrain pixels the beam burned

    def step(self) -> None:
        a = beam_angle(self.frame_index)
        end = (EMITTER[0] + REACH * math.cos(a), EMITTER[1] + REACH * math.sin(a))
        hit = self.world.raycast(EMITTER, end)
        self.beam = (EMITTER, hit.point if hit else end)
        if hit is not None:
            burned = hit.body.erase_circle(hit.point, BURN)
            self.edited(hit.body)
            if hit.body == self.terrain:
                self.hits.append((self.frame_index, hit.fraction))
                self.erased += burned
        super().step()

    def draw(self, surface) -> None:
        super().draw(surface)
        a, b = (self.to_screen(p) for p in self.beam)
        self.pg.draw.line(surface, (255, 60, 60), a, b, 3)
        self.pg.draw.circle(surface, (255, 220, 120), (round(b[0]), round(b[1])), 5)


def main(argv=None):
    return common.main(Laser, __doc__, argv)


if __name__ == "__main__":
    main()
