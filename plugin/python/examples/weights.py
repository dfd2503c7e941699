"""Weighted objects: paint mass into a body and watch its centre of mass move and the body respond.

Two identical planks balance on pivots, every pixel weighing 60 of 255. At frame 15 the brush paints the right
end of the left one at full weight 255 (the viewer's p tool): its centre of mass (yellow cross) moves right
by what the pixel sums say, the weight map (redder is heavier) shows the paint, and the plank tips right while
its unpainted twin stays level.
Run: python weights.py (p, then drag over a body to paint; -/= change the weight), or
python weights.py --frames 60 --screenshot weights.png
"""
from typing import Optional, Tuple

import numpy as np

import common
from physpix import World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
PLANK = (240, 14)          # width, height px
LIGHT, HEAVY = 60, 255     # the planks' weight, the paint's
PAINT_FRAME = 15
CENTERS = [(170.0, 200.0), (470.0, 200.0)]  # the planks' centres and pivots, px
# The brush strokes: world points along the right quarter of the left plank, radius 9 px.
STROKES = [(240.0 + 10 * i, 200.0) for i in range(6)]


class Weights(Viewer):
    """The scene in the viewer; it paints the strokes at PAINT_FRAME."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        block = common.sprite(np.ones((20, 16)), (110, 110, 120), edge=(80, 80, 90))
        look = common.sprite(np.ones(PLANK[::-1]), (176, 122, 64), edge=(110, 70, 30), border=1)
        self.planks = []
        for x, y in CENTERS:
            pivot = world.create_body(rgba=block, type="static", position=(x, y + PLANK[1] / 2 + 10))
            plank = world.create_body(rgba=look, weights=np.full(PLANK[::-1], LIGHT, np.uint8), position=(x, y))
            world.create_joint("revolute", pivot, plank, anchor_a=(x, y))
            self.planks.append(plank)
        super().__init__(world, size)
        self.painted = 0  # pixels the strokes changed

    def step(self) -> None:
        if self.frame_index == PAINT_FRAME:
            for at in STROKES:
                self.painted += self.brush("paint", at, 9.0, HEAVY)
        super().step()


def main(argv=None):
    return common.main(Weights, __doc__, argv)


if __name__ == "__main__":
    main()
