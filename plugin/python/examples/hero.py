"""A character on destructible ground: World.move_character walks, jumps and lands a capsule the program owns (not
a body), and a blast under its feet (World.explode) drops it into its own crater.

The arrows play it: left and right walk, up jumps from the ground, down blasts the ground under its feet. Until an
arrow is pressed it plays itself (PLAY): it walks right, jumps, lands and blasts.
Run: python hero.py, or python hero.py --frames 160 --screenshot hero.png
"""
from typing import Any, List, Optional, Tuple

import numpy as np

import common
from physpix import CharacterMove, World
from physpix.viewer import DT, Viewer

WIDTH, HEIGHT = 640, 360
GROUND_Y = 260.0                     # the ground's top, px
G = 980.0                            # px/s², down
RADIUS, HALF_HEIGHT = 6.0, 10.0      # the capsule, px: its foot RADIUS + HALF_HEIGHT below its position
START = (160.0, GROUND_Y - RADIUS - HALF_HEIGHT)
WALK_SPEED, JUMP_SPEED = 150.0, 420.0  # px/s
BLAST_RADIUS = 24.0                  # px: the crater under its feet
# The self-play: (first frame, last frame, what is held). Walk 40 frames, jump (about 50 frames in the air), blast.
PLAY = [(10, 49, "right"), (50, 50, "jump"), (130, 130, "blast")]


class Hero(Viewer):
    """The scene in the viewer and the character's game loop: the position and velocity are this program's."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, G))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        ground = common.sprite(np.ones((int(HEIGHT - GROUND_Y), WIDTH)), (122, 86, 52), edge=(70, 150, 60), border=4)
        self.ground = world.create_body(rgba=ground, type="static", position=(WIDTH / 2, (GROUND_Y + HEIGHT) / 2))
        box = common.sprite(np.ones((24, 24)), (214, 150, 70), edge=(120, 80, 40))
        self.crates = [world.create_body(rgba=box, position=(x, GROUND_Y - 12)) for x in (360.0, 480.0)]
        super().__init__(world, size)
        self.position, self.velocity = START, (0.0, 0.0)
        self.last: Optional[CharacterMove] = None  # the last move, its ground and what it met
        self.moves: List[CharacterMove] = []       # every frame's, for a test to read
        self.blasts: List[Tuple[float, float]] = []
        self.self_play = True                      # until an arrow is pressed
        self._jump = self._blast = False           # presses waiting for the next frame

    def held(self) -> Tuple[int, bool, bool]:
        """This frame's input: the walk direction (-1, 0, 1), a jump, a blast."""
        if self.self_play:
            now = {what for first, last, what in PLAY if first <= self.frame_index <= last}
            return ("right" in now) - ("left" in now), "jump" in now, "blast" in now
        keys = self.pg.key.get_pressed()
        jump, blast, self._jump, self._blast = self._jump, self._blast, False, False
        return keys[self.pg.K_RIGHT] - keys[self.pg.K_LEFT], jump, blast

    def step(self) -> None:
        walk, jump, blast = self.held()
        vy = self.velocity[1]
        if self.last is not None and self.last.grounded:
            vy = min(vy, 0.0)  # the ground took the fall; a jump's rise is kept
            if jump:
                vy = -JUMP_SPEED
        m = self.world.move_character(self.position, (walk * WALK_SPEED, vy + G * DT), DT, radius=RADIUS,
                                      half_height=HALF_HEIGHT)
        self.position, self.velocity, self.last = m.position, m.velocity, m
        self.moves.append(m)
        if blast:
            foot = (self.position[0], self.position[1] + HALF_HEIGHT + RADIUS)
            self.blasts.append(foot)
            self.blast(foot, BLAST_RADIUS)
        super().step()

    def handle(self, event: Any) -> bool:
        pg = self.pg
        arrows = (pg.K_LEFT, pg.K_RIGHT, pg.K_UP, pg.K_DOWN)
        if event.type == pg.KEYDOWN and event.key in arrows:  # the viewer's step key (right) is the walk here
            self.self_play = False
            self._jump = self._jump or event.key == pg.K_UP
            self._blast = self._blast or event.key == pg.K_DOWN
            return True
        return super().handle(event)

    def draw(self, surface: Any) -> None:
        super().draw(surface)
        pg = self.pg
        colour = (230, 70, 50)
        r = max(1, round(RADIUS * self.zoom))
        for dy in (-HALF_HEIGHT, HALF_HEIGHT):
            x, y = self.to_screen((self.position[0], self.position[1] + dy))
            pg.draw.circle(surface, colour, (round(x), round(y)), r)
        left, top = self.to_screen((self.position[0] - RADIUS, self.position[1] - HALF_HEIGHT))
        pg.draw.rect(surface, colour, (round(left), round(top), 2 * r, round(2 * HALF_HEIGHT * self.zoom)))


def main(argv=None):
    return common.main(Hero, __doc__, argv)


if __name__ == "__main__":
    main()
