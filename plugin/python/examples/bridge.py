"""A rope bridge that breaks: planks hung from two cliffs on revolute joints, and a heavy crate dropped on it.

One worn hinge has a break_force: it carries the bridge's own weight, but the crate's landing pulls it past it,
the world reports JOINT_BROKEN, and the two halves swing down to the cliffs as the crate falls through.
Run: python bridge.py, or python bridge.py --frames 150 --screenshot bridge.png
"""
import math
from typing import List, Optional, Tuple

import numpy as np

import common
from physpix import EventType, Joint, World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
DECK_Y = 180.0              # the planks' centre line at the cliffs, px
SAG = 40.0                  # how far the middle hangs below, px
GAP = (140.0, 500.0)        # the cliffs' inner edges, px
PLANKS = 18
BREAK_FORCE = 8.0e6         # mass·px/s²: 3 times what a joint carries with the bridge alone (2.5e6)
WORN = 11                   # the one hinge that breaks (the others hold any load), under the crate's landing
DROP_FRAME = 40


class Bridge(Viewer):
    """The scene in the viewer; it drops the crate at DROP_FRAME and keeps the broken joints it hears of."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        rock = common.sprite(np.ones((HEIGHT - 190, 150)), (110, 110, 120), edge=(80, 80, 90), border=3)
        for x in (GAP[0] - 75, GAP[1] + 75):
            world.create_body(rgba=rock, type="static", position=(x, 190 + (HEIGHT - 190) / 2))
        # Planks along a parabola that sags SAG px (a straight chain would need an endless pull to stay straight),
        # each hinged to the one before at their shared end.
        xs = np.linspace(GAP[0], GAP[1], PLANKS + 1)
        ys = DECK_Y + SAG * (1 - ((xs - xs.mean()) / (xs[-1] - xs.mean())) ** 2)
        self.planks = []
        self.joints: List[Joint] = []
        previous = None
        for i, (x0, y0, x1, y1) in enumerate(zip(xs[:-1], ys[:-1], xs[1:], ys[1:])):
            length = int(round(math.hypot(x1 - x0, y1 - y0))) - 1  # a pixel short: the hinges sit in the gaps
            wood = common.sprite(np.ones((6, length)), (176, 122, 64), edge=(110, 70, 30), border=1)
            plank = world.create_body(rgba=wood, position=((x0 + x1) / 2, (y0 + y1) / 2),
                                      angle=math.atan2(y1 - y0, x1 - x0))
            self.joints.append(world.create_joint("revolute", previous, plank, anchor_a=(x0, y0),
                                                  break_force=BREAK_FORCE if i == WORN else 0.0))
            self.planks.append(plank)
            previous = plank
        self.joints.append(world.create_joint("revolute", previous, None, anchor_a=(xs[-1], ys[-1])))
        super().__init__(world, size)
        self.crate_sprite = common.sprite(np.ones((40, 40)), (90, 90, 100), edge=(40, 40, 50), border=3)
        self.crate = None
        self.broken: List[Joint] = []  # the joints JOINT_BROKEN named

    def step(self) -> None:
        if self.frame_index == DROP_FRAME:  # an iron block, 8 times as dense as the planks
            self.crate = self.world.create_body(rgba=self.crate_sprite, position=(WIDTH / 2 + 30, 40.0), density=8)
        super().step()
        self.broken += [e.joint for e in self.world.events() if e.type == EventType.JOINT_BROKEN]


def main(argv=None):
    return common.main(Bridge, __doc__, argv)


if __name__ == "__main__":
    main()
