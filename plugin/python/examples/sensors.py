"""Sensors and one-way platforms: a sensor reports what passes through it without touching it, and a one-way
platform lets a body through from below and holds it from above.

A crate launched upward from the floor passes up through the platform (one_way) and lands on top of it; another
falls through the yellow sensor (is_sensor), which reports SENSOR_BEGIN and SENSOR_END, onto the floor.
Run: python sensors.py, or python sensors.py --frames 120 --screenshot sensors.png
"""
from typing import List, Optional, Tuple

import numpy as np

import common
from physpix import Event, EventType, World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
FLOOR_Y = 330.0              # the floor's top, px
PLATFORM = (220.0, 200.0)    # the one-way platform's centre, px; 160 × 10
SENSOR = (470.0, 230.0)      # the sensor's centre, px; 90 × 90
LAUNCH_FRAME, LAUNCH_SPEED = 10, 720.0   # frame, px/s upward: the crate rises about 260 px


class Sensors(Viewer):
    """The scene in the viewer; it launches the crate and keeps the sensor events."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        rock = common.sprite(np.ones((30, WIDTH)), (110, 110, 120), edge=(80, 80, 90), border=3)
        world.create_body(rgba=rock, type="static", position=(WIDTH / 2, FLOOR_Y + 15))
        board = common.sprite(np.ones((10, 160)), (90, 160, 210), edge=(40, 90, 140))
        self.platform = world.create_body(rgba=board, type="static", position=PLATFORM, one_way=True,
                                          one_way_direction=(0, -1))  # bodies may land from above (−y)
        glass = np.zeros((90, 90, 4), np.uint8)
        glass[...] = (230, 230, 80, 70)  # translucent: the mask, not the sprite's alpha, makes it solid
        self.sensor = world.create_body(rgba=glass, mask=np.ones((90, 90)), type="static", position=SENSOR,
                                        is_sensor=True)
        box = common.sprite(np.ones((24, 24)), (214, 150, 70), edge=(120, 80, 40))
        self.jumper = world.create_body(rgba=box, position=(PLATFORM[0], FLOOR_Y - 12))
        self.faller = world.create_body(rgba=box, position=(SENSOR[0], 40.0))
        super().__init__(world, size)
        self.sensed: List[Event] = []  # SENSOR_BEGIN and SENSOR_END, in order

    def step(self) -> None:
        if self.frame_index == LAUNCH_FRAME:
            self.jumper.velocity = (0.0, -LAUNCH_SPEED)
        super().step()
        self.sensed += [e for e in self.world.events()
                        if e.type in (EventType.SENSOR_BEGIN, EventType.SENSOR_END)]

    def draw(self, surface) -> None:
        super().draw(surface)
        if self._font is not None:
            said = ", ".join(e.type.name.lower() for e in self.sensed) or "nothing yet"
            surface.blit(self._font.render(f"sensor: {said}", True, (230, 230, 80)), (8, 24))


def main(argv=None):
    return common.main(Sensors, __doc__, argv)


if __name__ == "__main__":
    main()
