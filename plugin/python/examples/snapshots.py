"""Snapshots: save a world's whole state, load it back, and it runs on exactly as the original did.

A tower of crates stands on ground that a timed edit (World.schedule_erase) will blast at 0.75 s. At frame 30 the
world is saved (World.save_snapshot); at frame 75, with the tower falling, the viewer rewinds to the snapshot
(World.load_snapshot) and the same fall plays again, bit for bit: the timed edit is part of the saved state.
Keys: F5 saves, F9 loads the last save.
Run: python snapshots.py, or python snapshots.py --frames 100 --screenshot snapshots.png
"""
import tempfile
from pathlib import Path
from typing import Any, Optional, Tuple

import numpy as np

import common
from physpix import World
from physpix.viewer import Viewer

WIDTH, HEIGHT = 640, 360
SAVE_FRAME, REWIND_FRAME = 30, 75   # frames of 1/60 s
BLAST = (0.75, (300.0, 300.0), 40.0)   # world time (s: frame 45, between the save and the rewind), point, radius (px)


def same_states(a: Any, b: Any) -> bool:
    """Whether two World.body_states() arrays hold the same poses, velocities and sleep, bit for bit (the ids
    differ: a body's id names its world)."""
    fields = [f for f in a.dtype.names if f != "body"]
    return len(a) == len(b) and all(np.array_equal(a[f], b[f]) for f in fields)


class Snapshots(Viewer):
    """The scene in the viewer; it saves at SAVE_FRAME and rewinds at REWIND_FRAME."""

    def __init__(self, size: Optional[Tuple[int, int]] = None) -> None:
        world = World(gravity=(0, 980))
        world.camera = ((WIDTH / 2, HEIGHT / 2), 1.0, WIDTH, HEIGHT)
        ground = common.sprite(np.ones((60, WIDTH)), (96, 84, 72), edge=(70, 150, 60), border=4)
        world.create_body(rgba=ground, type="static", position=(WIDTH / 2, 330.0))
        box = common.sprite(np.ones((24, 24)), (214, 150, 70), edge=(120, 80, 40))
        for level in range(8):
            world.create_body(rgba=box, position=(300.0 + 3 * (level % 2), 288.0 - 24 * level))
        world.schedule_erase(*BLAST)
        super().__init__(world, size)
        self._folder = tempfile.TemporaryDirectory(prefix="physpix-snapshot-")
        self.snapshot = Path(self._folder.name) / "slot"
        self.saved_at: Optional[int] = None
        self.at_save: Any = None         # body states when saved
        self.before_rewind: Any = None   # body states at the rewind, of the world that ran on
        self.replayed: Any = None        # body states of the loaded world as many frames after the save

    def save_now(self) -> None:
        self.world.save_snapshot(self.snapshot)
        self.saved_at, self.at_save = self.frame_index, self.world.body_states()

    def load_saved(self) -> None:
        """Replace the world with the last snapshot; the frame count goes back with it."""
        if self.saved_at is None:
            return
        old, self.world = self.world, World.load_snapshot(self.snapshot)
        old.close()
        self.frame_index = self.saved_at
        self.selected, self._drag = None, None
        self.edited()

    def step(self) -> None:
        if self.frame_index == SAVE_FRAME and self.saved_at is None:
            self.save_now()
        elif self.frame_index == REWIND_FRAME and self.before_rewind is None:
            self.before_rewind = self.world.body_states()
            self.load_saved()
        elif self.frame_index == REWIND_FRAME and self.replayed is None:
            self.replayed = self.world.body_states()
        super().step()

    def handle(self, event: Any) -> bool:
        if event.type == self.pg.KEYDOWN and event.key in (self.pg.K_F5, self.pg.K_F9):
            self.save_now() if event.key == self.pg.K_F5 else self.load_saved()
            return True
        return super().handle(event)

    def draw(self, surface: Any) -> None:
        super().draw(surface)
        if self._font is not None and self.saved_at is not None:
            text = f"saved at frame {self.saved_at}"
            if self.replayed is not None:
                same = same_states(self.before_rewind, self.replayed)
                text += f"; rewound at {REWIND_FRAME}: the replay {'matches' if same else 'differs'}"
            surface.blit(self._font.render(text, True, (150, 220, 255)), (8, 24))


def main(argv=None):
    return common.main(Snapshots, __doc__, argv)


if __name__ == "__main__":
    main()
