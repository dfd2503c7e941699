"""python -m physpix.viewer headless: a picture of the demo, and scripted painting sessions whose mass properties and
motion are checked against the pixel sums and free fall."""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import physpix

REPO = Path(__file__).resolve().parents[2]
os.environ["SDL_VIDEODRIVER"] = "dummy"  # before pygame opens a display
os.environ["SDL_AUDIODRIVER"] = "dummy"
os.environ["PYGAME_HIDE_SUPPORT_PROMPT"] = "1"


def _env():
    env = dict(os.environ, PYTHONPATH=str(REPO / "plugin" / "python"))
    return env


def test_without_pygame_says_how_to_install():
    # A None in sys.modules makes `import pygame` fail as if it were not installed.
    code = "import sys; sys.modules['pygame'] = None; from physpix.viewer import main; sys.exit(main([]))"
    run = subprocess.run([sys.executable, "-c", code], env=_env(), capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert "pip install 'physpix[viewer]'" in run.stderr


pygame = pytest.importorskip("pygame", reason="pygame is not installed: pip install 'physpix[viewer]' "
                                              "(make deps installs it into build/venv)")
from physpix.viewer import Viewer  # noqa: E402


def test_demo_headless_screenshot(tmp_path):
    out = tmp_path / "demo.png"
    run = subprocess.run([sys.executable, "-m", "physpix.viewer", str(REPO / "demo" / "scene.json"), "--frames", "30",
                          "--screenshot", str(out), "--size", "480", "270"],
                         env=_env(), capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    picture = physpix.load_png(out)
    assert picture.shape == (270, 480, 4)
    assert (picture[..., 3] == 255).all()
    # Sprites, terrain and the overlay's colours, not a cleared window.
    assert len(np.unique(picture.reshape(-1, 4), axis=0)) > 100


def _plank_scene(folder):
    """A 100×10 plank of weight 51 on a revolute joint at its centre (200, 100), above a static pivot."""
    physpix.save_png(folder / "plank_weights.png", np.full((10, 100, 4), 51, np.uint8))
    scene = {"world": {"gravity": [0, 980]},
             "camera": {"center": [200, 100], "zoom": 1, "width": 320, "height": 180},
             "bodies": [{"name": "pivot", "type": "static", "box": [6, 6], "position": [200, 110]},
                        {"name": "plank", "box": [100, 10], "weights": "plank_weights.png", "position": [200, 100],
                         "density": 2}],
             "joints": [{"type": "revolute", "body_a": "pivot", "body_b": "plank", "anchor_a": [200, 100]}]}
    path = folder / "plank.json"
    path.write_text(json.dumps(scene))
    return path


def _com_x(weights):
    return float((weights.astype(np.float64) * (np.arange(weights.shape[1]) + 0.5)).sum() / weights.sum())


def test_painting_the_left_half_moves_the_centre_of_mass_and_tips_the_plank(tmp_path):
    world = physpix.World.load_scene(_plank_scene(tmp_path))
    plank = next(b for b in world.bodies() if b.type == physpix.BodyType.DYNAMIC)
    assert plank.center_of_mass == pytest.approx((50.0, 5.0), abs=1e-4)
    strokes = [{"frame": 0, "tool": "paint", "at": [155 + 10 * i, 100], "radius": 6, "weight": 255} for i in range(4)]
    script = strokes + [{"frame": 0, "tool": "save", "at": [200, 100], "dir": str(tmp_path / "saved"),
                         "name": "plank"}]
    viewer = Viewer(world, (320, 180))
    viewer.run(1, script, interactive=False)  # the strokes and the save come before the first step

    # The pixels the strokes reach: centres within 6 px of a stroke, the plank's top-left corner at (150, 95).
    ys, xs = np.mgrid[0:10, 0:100] + 0.5
    painted = np.zeros((10, 100), bool)
    for s in strokes:
        painted |= np.hypot(xs + 150 - s["at"][0], ys + 95 - s["at"][1]) <= 6
    expected = np.where(painted, 255, 51).astype(np.uint8)
    saved = physpix.load_png(tmp_path / "saved" / "plank_weights.png")[..., 0]
    assert np.array_equal(saved, expected)
    assert painted[:, 50:].sum() == 0 and painted.sum() > 300
    com = plank.center_of_mass
    assert com[0] == pytest.approx(_com_x(expected), abs=1e-3)
    assert com[0] < 50 - 5
    assert plank.mass == pytest.approx(2 * expected.sum() / 255.0, rel=1e-5)

    # Heavier on the left: the left end goes down, which turns +x toward -y (a negative angle).
    viewer.run(40, interactive=False)
    assert plank.angle < -0.2

    # The saved planes load back as a scene with the same mass properties.
    loaded = physpix.World.load_scene(tmp_path / "saved" / "plank.json")
    (copy,) = loaded.bodies()
    assert copy.mass == pytest.approx(plank.mass, abs=1e-4)
    assert copy.center_of_mass == pytest.approx(com, abs=1e-4)
    assert copy.size == (100, 10)
    world.close()
    loaded.close()


def test_erasing_under_a_crate_drops_it(tmp_path):
    with physpix.World(gravity=(0, 980), backend="cpu") as world:
        world.create_body(np.ones((20, 200), np.uint8), type="static", position=(200, 200))
        crate = world.create_body(np.ones((20, 20), np.uint8), position=(200, 179.5))
        viewer = Viewer(world, (320, 180))
        # The erase takes the whole 20 px depth of the floor for 23 px each side of the crate's centre.
        viewer.run(40, [{"frame": 40, "tool": "erase", "at": [200, 200], "radius": 25}], interactive=False)
        rest = crate.position[1]
        assert rest == pytest.approx(179.5, abs=1.5)  # resting, within the contacts' allowed overlap
        viewer.run(70, interactive=False)  # the erase, then 30 frames of fall
        t = 30 / 60
        assert crate.position[1] - rest == pytest.approx(0.5 * 980 * t * t, rel=0.05)  # free fall
