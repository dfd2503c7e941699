"""What hosts build scenes and views from: PNG out, the world clock, timed edits, the camera, a body's look,
a pair's debug grid, JSON scenes and snapshots that continue bit for bit."""
import json
import math

import numpy as np
import pytest

import physpix
from physpix import CELL_A, CELL_B, CELL_CRITICAL, BodyType, Camera, EditType, World
from pphelpers import angle_between_deg, raises_from_library, rect

DT = 1 / 60

# A static 400×40 ground (top at y = 380) and a 32×32 crate dropped from 64 px above it.
SCENE = {"world": {"gravity": [0, 980]},
         "bodies": [{"name": "ground", "type": "static", "box": [400, 40], "position": [200, 400]},
                    {"name": "crate", "box": [32, 32], "position": [200, 300]}]}


def write_scene(tmp_path, scene, name="scene.json"):
    path = tmp_path / name
    path.write_text(json.dumps(scene))
    return path


def slab(world):
    """A static 200×40 slab centred at (100, 100)."""
    return rect(world, 200, 40, type="static", position=(100, 100))


def test_png_save_then_load_is_exact(tmp_path):
    rgba = np.random.default_rng(6).integers(0, 256, size=(37, 53, 4), dtype=np.uint8)
    physpix.save_png(tmp_path / "r.png", rgba)
    assert physpix.image_info(tmp_path / "r.png") == (53, 37)
    assert np.array_equal(physpix.load_png(tmp_path / "r.png"), rgba)


def test_save_png_checks_the_array_and_the_library_the_file(tmp_path):
    with pytest.raises(ValueError, match="shape"):
        physpix.save_png(tmp_path / "a.png", np.zeros((4, 4, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="uint8"):
        physpix.save_png(tmp_path / "a.png", np.zeros((4, 4, 4), dtype=np.float32))
    raises_from_library(physpix.PhysPixIOError, ["no_such_folder"], physpix.save_png,
                        tmp_path / "no_such_folder" / "a.png", np.zeros((4, 4, 4), dtype=np.uint8))


def test_time_is_the_sum_of_the_steps(world):
    assert world.time == 0.0
    steps = [DT] * 30 + [1 / 30] * 15 + [0.25]
    for dt in steps:
        world.step(dt)
    # The library adds each dt as the float it received.
    assert world.time == pytest.approx(sum(float(np.float32(dt)) for dt in steps), abs=1e-9)
    assert world.time == pytest.approx(1.25, abs=1e-5)


def test_a_scheduled_erase_applies_at_the_step_nearest_its_time(world):
    ground = slab(world)
    world.schedule_erase(0.5, (100, 100), 10)
    full = int(ground.read_mask().sum())
    assert full == 200 * 40
    # Step 30 starts at 29/60 < 0.5 − dt/2: untouched; step 31 starts at 30/60 = 0.5: applied.
    for _ in range(30):
        world.step(DT)
    assert int(ground.read_mask().sum()) == full
    assert len(world.scheduled_edits()) == 1
    world.step(DT)
    erased = full - int(ground.read_mask().sum())
    assert 300 <= erased <= 330, erased  # a disc of radius 10 px by pixel centres: π·10² ≈ 314
    assert world.scheduled_edits() == []


def test_scheduled_edits_list_in_time_order_and_paint_refills(space):
    ground = slab(space)
    space.schedule_paint(0.2, ground, (50, 100), 6, weight=255)
    space.schedule_erase(0.1, (50, 100), 6, body=ground)
    edits = space.scheduled_edits()
    assert [(e.time, e.type, e.body) for e in edits] == [(0.1, EditType.ERASE_CIRCLE, ground),
                                                         (0.2, EditType.PAINT_CIRCLE, ground)]
    assert edits[1].center == (50.0, 100.0) and edits[1].radius == 6.0 and edits[1].weight == 255
    for _ in range(9):
        space.step(DT)
    assert ground.read_mask().sum() < 200 * 40
    for _ in range(6):
        space.step(DT)
    assert ground.read_mask().sum() == 200 * 40


def test_timed_edit_refusals(space):
    ground = slab(space)
    for weight in (-1, 256, 2**32):  # would wrap in the 32-bit field
        with pytest.raises(ValueError, match="weight"):
            space.schedule_paint(1, ground, (0, 0), 4, weight=weight)
    raises_from_library(physpix.InvalidArgumentError, ["1..255"], space.schedule_paint, 1, ground, (0, 0), 4, 0)
    raises_from_library(physpix.InvalidArgumentError, ["finite"], space.schedule_erase, math.nan, (0, 0), 4)
    raises_from_library(physpix.InvalidArgumentError, ["radius"], space.schedule_erase, 1, (0, 0), -1)
    raises_from_library(physpix.InvalidArgumentError, ["needs a body"], space.schedule_paint, 1, None, (0, 0), 4)
    assert space.scheduled_edits() == []


def test_camera_set_get_and_refusals(world):
    assert world.camera == Camera((480.0, 270.0), 1.0, 960, 540)
    world.camera = Camera((10, 20), 2.5, 320, 200)
    assert world.camera == Camera((10.0, 20.0), 2.5, 320, 200)
    world.camera = ((-5, 7), 0.5, 64, 48)
    assert world.camera == Camera((-5.0, 7.0), 0.5, 64, 48)
    raises_from_library(physpix.InvalidArgumentError, ["zoom"], setattr, world, "camera", ((0, 0), 0, 64, 48))
    raises_from_library(physpix.InvalidArgumentError, ["size"], setattr, world, "camera", ((0, 0), 1, 0, 48))
    raises_from_library(physpix.InvalidArgumentError, ["finite"], setattr, world, "camera",
                        ((math.inf, 0), 1, 64, 48))
    with pytest.raises(ValueError, match="width"):
        world.camera = ((0, 0), 1, 2**32 + 64, 48)  # ctypes would wrap it to a valid 64
    assert world.camera == Camera((-5.0, 7.0), 0.5, 64, 48), "a refused camera changed the world's"


def test_read_rgba_is_the_sprite_where_solid(space):
    sprite = np.random.default_rng(3).integers(0, 256, size=(8, 40, 4), dtype=np.uint8)
    sprite[..., 3] = 255
    sprite[:, 0, 3] = 0  # a transparent first column is not solid
    bar = space.create_body(rgba=sprite, position=(100, 100), custom_pivot=1, pivot=(3, 4), type="kinematic")
    look = bar.read_rgba()
    assert look.shape == (8, 40, 4) and look.dtype == np.uint8
    solid = bar.read_mask().astype(bool)
    assert np.array_equal(solid, sprite[..., 3] >= 128)
    assert np.array_equal(look[solid], sprite[solid])
    assert not look[~solid].any()
    assert bar.pivot == (3.0, 4.0)
    assert bar.type is BodyType.KINEMATIC


def test_debug_collision_of_a_box_sunk_3_px_into_the_ground():
    with World(backend="cpu", normal_method="kernel") as w:
        ground = rect(w, 200, 40, type="static", position=(100, 100))  # top at y = 80
        box = rect(w, 32, 32, position=(100, 80 - 16 + 3))
        cells, normals, view = w.debug_collision(box, ground)
        assert cells.shape == (view.height, view.width) and cells.dtype == np.uint8
        assert normals.shape == (view.height, view.width, 2) and normals.dtype == np.float32
        both = (cells & (CELL_A | CELL_B)) == CELL_A | CELL_B
        critical = (cells & CELL_CRITICAL) != 0
        assert view.intersection == both.sum() == 32 * 3
        assert view.intersection == w.collide(box, ground)[0].pixel_count
        assert view.normal == pytest.approx((0.0, 1.0), abs=1e-6)
        assert view.critical == critical.sum() > 0 and not (critical & ~both).any()
        assert not normals[~critical].any(), "only critical cells have local normals"
        assert angle_between_deg(normals[critical].sum(axis=0), view.normal) < 1.0

        swapped, _, turned = w.debug_collision(ground, box)
        assert turned.normal == pytest.approx((0.0, -1.0), abs=1e-6)
        assert np.array_equal(swapped, (cells & CELL_CRITICAL) | (cells & CELL_A) << 1 | (cells & CELL_B) >> 1)

        box.position = (100, 0)
        cells, normals, view = w.debug_collision(box, ground)
        assert cells.shape == (0, 0) and view.intersection == 0 and view.normal == (0.0, 0.0)
        raises_from_library(physpix.InvalidArgumentError, ["same body"], w.debug_collision, box, box)


def test_a_scene_crate_comes_to_rest_on_its_ground(tmp_path):
    with World.load_scene(write_scene(tmp_path, SCENE)) as w:
        ground, crate = w.bodies()
        assert (ground.type, crate.type) == (BodyType.STATIC, BodyType.DYNAMIC)
        assert ground.size == (400, 40) and crate.size == (32, 32)
        assert crate.position == (200.0, 300.0) and crate.pivot == (16.0, 16.0)
        for _ in range(120):
            w.step(DT)
        bottom = crate.position[1] + 16
        assert abs(bottom - 380) <= 1.5, f"crate bottom at y = {bottom}, ground top at 380"
        assert abs(crate.position[0] - 200) < 0.5 and abs(crate.angle) < 0.01


def test_a_malformed_scene_names_the_json_path(tmp_path):
    bad = json.loads(json.dumps(SCENE))
    bad["bodies"][0]["density"] = -1
    raises_from_library(physpix.FormatError, ["bodies[0].density: expected a number > 0"], World.load_scene,
                        write_scene(tmp_path, bad))
    raises_from_library(physpix.PhysPixIOError, ["missing.json"], World.load_scene, tmp_path / "missing.json")


def poses(world):
    return [(b.position, b.angle, b.velocity, b.angular_velocity) for b in world.bodies()]


def test_a_snapshot_continues_bit_for_bit(tmp_path):
    with World(backend="cpu", substeps=3) as w:
        rect(w, 400, 40, type="static", position=(200, 400))
        for i in range(4):  # a leaning stack: contacts, rotation and sleep all matter
            rect(w, 32, 24, position=(190 + 5 * i, 340 - 30 * i), angle=0.05 * i, friction=0.3)
        rect(w, 20, 20, position=(120, 200), linear_velocity=(40, 0), angular_velocity=2, restitution=0.4)
        w.schedule_erase(1.5, (200, 380), 12)  # pending across the snapshot
        for _ in range(60):
            w.step(DT)
        w.save_snapshot(tmp_path / "snap")
        expected = []
        for _ in range(120):
            w.step(DT)
            expected.append(poses(w))
        end_time = w.time

    with World.load_snapshot(tmp_path / "snap") as restored:
        assert restored.time == pytest.approx(1.0, abs=1e-5)
        assert [e.time for e in restored.scheduled_edits()] == [1.5]
        got = []
        for _ in range(120):
            restored.step(DT)
            got.append(poses(restored))
        assert restored.time == end_time
    for i, (g, e) in enumerate(zip(got, expected)):
        assert g == e, f"step {i + 1} after the snapshot differs"


def test_state_in_memory_restores_loads_and_hashes():
    """A world saved as bytes, stepped, restored and stepped again retraces its steps; a body made after the save
    goes stale; a loaded world hashes alike; changed bytes raise FormatError and change nothing."""
    world = World(gravity=(0, 980))
    rect(world, 400, 40, type=BodyType.STATIC, position=(200, 300))
    crates = [rect(world, 16, 16, position=(100 + 40 * i, 200 - 30 * i)) for i in range(5)]
    for _ in range(20):
        world.step(1 / 60)
    data = world.save_state()
    assert isinstance(data, bytes) and len(data) > 400 * 40 // 8
    h = world.hash
    late = rect(world, 8, 8, position=(50, 50))
    for _ in range(30):
        world.step(1 / 60)
    first = [c.position for c in crates]
    assert world.hash != h
    world.restore_state(data)
    assert world.hash == h
    with pytest.raises(physpix.InvalidHandleError):
        late.position
    rect(world, 8, 8, position=(50, 50))  # as late was, so that the future is the same
    for _ in range(30):
        world.step(1 / 60)
    assert [c.position for c in crates] == first
    copy = World.load_state(data)
    assert copy.hash == h and copy.hash != world.hash
    broken = bytearray(data)
    broken[len(data) // 2] ^= 1
    now = world.hash
    raises_from_library(physpix.FormatError, ["checksum"], copy.restore_state, bytes(broken))
    raises_from_library(physpix.InvalidArgumentError, ["saved from world"], world.restore_state, data[:0] + copy.save_state())
    assert world.hash == now
    copy.close()
    world.close()
