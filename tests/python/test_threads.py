"""A World shared by threads: its calls run one at a time (ctypes lets go of the GIL inside a library call, and
two threads inside one world at once corrupted it: 4 of 5 runs of the issue's 4-thread script crashed)."""
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import physpix

PACKAGE_ROOT = Path(__file__).resolve().parents[2] / "plugin" / "python"

# Four threads step, create, erase, destroy and read one World; afterwards its clock and bodies are what the calls
# add up to, as if they had run one after another. A box may move between a thread reading its position and
# erasing there, so an erase can cut a corner off: the split events count those pieces.
SHARED_WORLD = textwrap.dedent("""
    import threading
    import numpy as np
    import physpix

    world = physpix.World(backend="cpu", worker_threads=1)
    world.create_body(mask=np.ones((20, 400)), type="static", position=(200, 300))
    STEPS, THREADS = 100, 4
    seen = []  # every thread's events (reading forgets them)

    def work(k):
        for i in range(STEPS):
            box = world.create_body(mask=np.ones((8, 8)), position=(40 + 80 * k, 100 + (i % 10) * 10))
            world.step(1 / 240)
            box.erase_circle(box.position, 2)
            world.body_states(), world.contacts()
            seen.extend(world.events())
            if i % 2:
                box.destroy()

    threads = [threading.Thread(target=work, args=(k,)) for k in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert abs(world.time - STEPS * THREADS / 240) < 1e-6, world.time
    seen.extend(world.events())
    pieces = sum(e.type == physpix.EventType.BODY_SPLIT for e in seen)
    gone = sum(e.type == physpix.EventType.BODY_DESTROYED for e in seen)
    assert len(world.bodies()) == 1 + THREADS * STEPS // 2 + pieces - gone, (len(world.bodies()), pieces, gone)
    print("shared world ok")
""")


def test_a_world_shared_by_four_threads_runs_their_calls_one_at_a_time():
    # In a child process, so that a crash fails this test rather than ending the session.
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(PACKAGE_ROOT), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, "-c", SHARED_WORLD], env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and "shared world ok" in run.stdout, \
        f"exit {run.returncode}\nstdout: {run.stdout[-2000:]}\nstderr: {run.stderr[-2000:]}"


@pytest.mark.parametrize("shape, name", [((1, 2 ** 32 + 16), "mask width"), ((2 ** 32 + 16, 1), "mask height")])
def test_a_mask_too_large_for_the_c_types_is_a_value_error_naming_it(world, shape, name):
    # Before issue 39 a (1, 2**32 + 16) mask made a 16×1 body: ctypes wrapped the width to 16. A broadcast array
    # holds that shape in one byte; the check comes before anything copies it.
    huge = np.broadcast_to(np.uint8(1), shape)
    with pytest.raises(ValueError, match=name):
        world.create_body(mask=huge)
    with pytest.raises(ValueError, match=name.replace("mask", "weights")):
        world.create_body(mask=np.ones((1, 16)), weights=np.broadcast_to(np.uint8(255), shape))
    assert world.bodies() == []


def test_an_image_too_large_for_the_c_types_is_a_value_error_naming_it(world, tmp_path):
    huge = np.broadcast_to(np.uint8(255), (1, 2 ** 32 + 16, 4))
    with pytest.raises(ValueError, match="rgba width"):
        world.create_body(rgba=huge)
    with pytest.raises(ValueError, match="rgba width"):
        physpix.save_png(tmp_path / "huge.png", huge)
    box = world.create_body(mask=np.ones((4, 4)))
    with pytest.raises(ValueError, match="mask width"):
        box.write_pixels(0, 0, np.broadcast_to(np.uint8(1), (1, 2 ** 32 + 16)))
    assert not (tmp_path / "huge.png").exists() and box.read_mask().sum() == 16
