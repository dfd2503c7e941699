"""plugin/python/examples headless: each example runs its scene for a few seconds of world time, writes a picture
that is not blank, and does the physics it shows (a crater under a crate, a broken hinge, a moved centre of mass, a
burned trench, a sensor's events and a one-way landing, a snapshot's replay bit for bit)."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import physpix

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "plugin" / "python" / "examples"
os.environ["SDL_VIDEODRIVER"] = "dummy"  # before pygame opens a display
os.environ["SDL_AUDIODRIVER"] = "dummy"
os.environ["PYGAME_HIDE_SUPPORT_PROMPT"] = "1"

pygame = pytest.importorskip("pygame", reason="pygame is not installed: pip install 'physpix[viewer]' "
                                              "(make deps installs it into build/venv)")
sys.path.insert(0, str(EXAMPLES))
import bridge  # noqa: E402
import hero  # noqa: E402
import laser  # noqa: E402
import sensors  # noqa: E402
import snapshots  # noqa: E402
import terrain  # noqa: E402
import weights  # noqa: E402
sys.path.remove(str(EXAMPLES))


def run_example(example, frames, tmp_path, size=(320, 180)):
    """The example's viewer after `frames` headless frames of its command line, which wrote its last frame."""
    shot = tmp_path / "last.png"
    viewer = example.main(["--frames", str(frames), "--screenshot", str(shot), "--size", *map(str, size)])
    picture = physpix.load_png(shot)
    assert picture.shape == (size[1], size[0], 4)
    # Sprites and overlay in many colours, not a cleared window.
    assert len(np.unique(picture.reshape(-1, 4), axis=0)) > 30, f"{example.__name__}: the picture is nearly blank"
    return viewer


def solid_pixels(world):
    return sum(int(b.read_mask().sum()) for b in world.bodies())


def test_terrain_blasts_take_the_pixels_they_count_and_drop_the_crates(tmp_path):
    viewer = terrain.Terrain((320, 180))
    before = solid_pixels(viewer.world)
    viewer.run(terrain.BLASTS[0][0], interactive=False)  # settled, just before the first blast
    rest = [c.position[1] for c in viewer.crates]
    viewer = run_example(terrain, 120, tmp_path)
    assert viewer.erased > 3000  # three craters of radius 28 px, cut into terrain and crates
    assert solid_pixels(viewer.world) == before - viewer.erased
    drops = [c.position[1] - y for c, y in zip(viewer.crates, rest) if c.world is viewer.world]
    assert max(drops) > 20, f"no crate fell into its crater: {drops}"


def test_bridge_breaks_at_its_worn_hinge_and_the_crate_falls_through(tmp_path):
    viewer = run_example(bridge, 120, tmp_path)
    assert viewer.broken == [viewer.joints[bridge.WORN]], "the worn hinge alone breaks"
    assert len(viewer.world.joints()) == len(viewer.joints) - 1
    # The crate fell through the gap, below the sagging deck and on down.
    assert viewer.crate.position[1] > bridge.DECK_Y + bridge.SAG + 200
    # Each half hangs from its cliff: its end plank still 10 px (half a plank) from the hinge, its free end far below.
    half = (bridge.GAP[1] - bridge.GAP[0]) / bridge.PLANKS / 2
    assert math.dist(viewer.planks[0].position, (bridge.GAP[0], bridge.DECK_Y)) == pytest.approx(half, abs=1.5)
    assert math.dist(viewer.planks[-1].position, (bridge.GAP[1], bridge.DECK_Y)) == pytest.approx(half, abs=1.5)
    for loose in viewer.planks[bridge.WORN - 1:bridge.WORN + 1]:
        assert loose.position[1] > bridge.DECK_Y + bridge.SAG + 60


def test_painted_weight_moves_the_centre_of_mass_and_tips_the_plank(tmp_path):
    viewer = run_example(weights, 60, tmp_path)
    painted, twin = viewer.planks
    plane = painted.read_weights().astype(np.float64)
    assert viewer.painted > 300 and (plane == weights.HEAVY).sum() == viewer.painted
    # The centre of mass is the weighted mean of the pixel centres, and the mass their sum.
    cx = (plane * (np.arange(plane.shape[1]) + 0.5)).sum() / plane.sum()
    assert painted.center_of_mass[0] == pytest.approx(cx, abs=1e-3)
    assert cx > weights.PLANK[0] / 2 + 20
    assert painted.mass == pytest.approx(plane.sum() / 255, rel=1e-5)
    assert twin.center_of_mass[0] == pytest.approx(weights.PLANK[0] / 2, abs=1e-4)
    # Heavier on the right: the right end goes down (+x toward +y, a positive angle); the twin stays level.
    assert painted.angle > 0.3 and abs(twin.angle) < 1e-3


def test_laser_burns_a_trench_deeper_on_its_second_sweep(tmp_path):
    viewer = run_example(laser, 4 * laser.SWEEP_FRAMES, tmp_path)  # two sweeps down and up
    full = viewer.terrain.size[0] * viewer.terrain.size[1]
    assert viewer.erased > 2000 and int(viewer.terrain.read_mask().sum()) == full - viewer.erased
    # Frames f and 4·SWEEP_FRAMES − 1 − f aim the same way: the later beam meets the ground farther on.
    hits = dict(viewer.hits)
    last = 4 * laser.SWEEP_FRAMES - 1
    pairs = [(hits[f], hits[last - f]) for f in range(laser.SWEEP_FRAMES) if f in hits and last - f in hits]
    assert len(pairs) > laser.SWEEP_FRAMES // 2
    assert all(later > first for first, later in pairs), pairs
    assert laser.beam_angle(3) == laser.beam_angle(last - 3)


def test_sensor_reports_the_faller_and_the_platform_holds_the_jumper_from_above(tmp_path):
    viewer = run_example(sensors, 120, tmp_path)
    said = [(e.type, e.body, e.other) for e in viewer.sensed]
    assert said == [(physpix.EventType.SENSOR_BEGIN, viewer.sensor, viewer.faller),
                    (physpix.EventType.SENSOR_END, viewer.sensor, viewer.faller)]
    # The sensor did not touch it: it fell on to the floor.
    assert viewer.faller.position[1] == pytest.approx(sensors.FLOOR_Y - 12, abs=1.5)
    # Launched from the floor, the jumper passed up through the platform and stands on it.
    assert viewer.jumper.position[1] == pytest.approx(sensors.PLATFORM[1] - 5 - 12, abs=1.5)
    assert not viewer.jumper.is_awake or abs(viewer.jumper.velocity[1]) < 5


def test_snapshot_replays_the_fall_bit_for_bit(tmp_path):
    viewer = run_example(snapshots, snapshots.REWIND_FRAME + 10, tmp_path)
    assert viewer.saved_at == snapshots.SAVE_FRAME
    assert not snapshots.same_states(viewer.at_save, viewer.before_rewind), "nothing moved between save and rewind"
    assert snapshots.same_states(viewer.before_rewind, viewer.replayed)
    falling = viewer.before_rewind["linear_velocity"]
    assert np.hypot(falling[:, 0], falling[:, 1]).max() > 10  # the blast had the tower moving


def test_an_example_runs_as_a_newcomer_types_it(tmp_path):
    # No PYTHONPATH: the example finds the package beside its folder.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = tmp_path / "sensors.png"
    run = subprocess.run([sys.executable, str(EXAMPLES / "sensors.py"), "--frames", "5", "--screenshot", str(out)],
                         env=env, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert physpix.load_png(out).shape == (360, 640, 4)


def test_hero_walks_jumps_lands_and_blasts_itself_into_a_crater(tmp_path):
    """The self-play (hero.PLAY): walk right 40 frames at 150 px/s, jump, land, blast the ground under its feet."""
    viewer = run_example(hero, 160, tmp_path)
    moves = viewer.moves
    start_y = hero.START[1]
    walked = moves[10:50]
    assert all(m.grounded and abs(m.position[1] - start_y) <= 0.5 for m in walked)
    assert walked[-1].position[0] - hero.START[0] == pytest.approx(hero.WALK_SPEED * 40 * hero.DT, rel=0.02)
    air = [i for i, m in enumerate(moves) if not m.grounded]
    # Two flights: the jump from frame 50, and the fall into the crater after the blast of frame 130.
    landing = next(i for i in air if i + 1 not in air)
    assert air[0] == 50 and air[:landing - 49] == list(range(50, landing + 1))
    assert air[landing - 49:] and air[landing - 49] == 131 and air[-1] < len(moves) - 1
    peak = start_y - min(m.position[1] for m in moves[50:landing + 1])
    assert peak == pytest.approx(hero.JUMP_SPEED ** 2 / (2 * hero.G), rel=0.05)
    landed = moves[landing + 1]
    assert landed.grounded and abs(landed.position[1] - start_y) <= 0.5 and landed.ground_body == viewer.ground
    # The blast at its feet on the old ground; it ends grounded on the crater's floor, BLAST_RADIUS below.
    assert viewer.blasts == [pytest.approx((moves[130].position[0], hero.GROUND_Y), abs=0.5)]
    end = moves[-1]
    assert end.grounded and end.ground_body == viewer.ground
    assert end.position[0] == pytest.approx(viewer.blasts[0][0], abs=1)
    assert end.position[1] + hero.HALF_HEIGHT + hero.RADIUS == pytest.approx(hero.GROUND_Y + hero.BLAST_RADIUS, abs=1)
