"""What every example shares: its command line, the viewer's window around it, and a headless run for tests.

`python NAME.py` opens a window (pygame: pip install 'physpix[viewer]'); `--frames N --screenshot out.png` runs N
frames of 1/60 s without one (SDL_VIDEODRIVER=dummy) and writes the last frame.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Callable, Optional, Sequence, Tuple, TypeVar

try:
    import physpix  # noqa: F401
except ImportError:  # run from a checkout after `make all`: the package beside this folder
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from physpix import DEBUG_DRAW_AABBS  # noqa: E402
from physpix.viewer import INSTALL_HINT, Viewer  # noqa: E402

V = TypeVar("V", bound=Viewer)


def sprite(mask: np.ndarray, rgb: Tuple[int, int, int], edge: Tuple[int, int, int] = (0, 0, 0),
           border: int = 2) -> np.ndarray:
    """An RGBA sprite of a mask: rgb inside, `edge` on the pixels within `border` px of the outside, clear
    elsewhere. The sprite alone makes a body: its opaque pixels are the solid ones."""
    solid = np.asarray(mask).astype(bool)
    inner = solid.copy()
    for _ in range(border):  # erode by one pixel (4-neighbours), the bitmap's outside counting as empty
        p = np.pad(inner, 1)
        inner = inner & p[:-2, 1:-1] & p[2:, 1:-1] & p[1:-1, :-2] & p[1:-1, 2:]
    rgba = np.zeros(solid.shape + (4,), np.uint8)
    rgba[solid] = (*rgb, 255)
    rgba[solid & ~inner, :3] = edge
    return rgba


def main(build: Callable[[Optional[Tuple[int, int]]], V], doc: str,
         argv: Optional[Sequence[str]] = None) -> Optional[V]:
    """Parse the example's command line, build its viewer (for a window size, None: the camera's) and run it; the
    viewer after the run, for a test to look at (None: no pygame)."""
    parser = argparse.ArgumentParser(description=doc.strip().split("\n")[0])
    parser.add_argument("--frames", type=int, default=0, help="run this many frames headless, then exit (0: a window)")
    parser.add_argument("--screenshot", help="write the last frame to this PNG")
    parser.add_argument("--size", type=int, nargs=2, metavar=("W", "H"), help="window size (default: the camera's)")
    args = parser.parse_args(argv)
    headless = args.frames > 0
    if headless:
        os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # before pygame opens a display
        os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        import pygame  # noqa: F401
    except ImportError:
        print(INSTALL_HINT, file=sys.stderr)
        return None
    viewer = build((args.size[0], args.size[1]) if args.size else None)
    viewer.flags &= ~DEBUG_DRAW_AABBS  # boxes around the static ground would frame the view; key 2 shows them
    viewer.run(args.frames, screenshot=args.screenshot, interactive=not headless)
    return viewer
