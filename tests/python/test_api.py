"""The Python surface: enums as strings, properties and setters, handles as values, PNG in, packaging."""
import math

import numpy as np
import pytest

import physpix
from physpix import Backend, BodyType, ContactMode, NormalMethod
from pphelpers import png_bytes, rect


def test_library_version_is_major_0():
    assert physpix.library_version[0] == 0


@pytest.mark.parametrize("fields", [
    dict(backend="cpu", normal_method="kernel", contact_mode="centroid"),
    dict(backend=Backend.CPU, normal_method=NormalMethod.AREA_GRADIENT, contact_mode=ContactMode.MANIFOLD),
    dict(backend="CPU", substeps=4, solver_iterations=30, exact_solver=True, allow_sleep=False, raster_stride=2),
])
def test_world_accepts_def_fields_as_keywords(fields):
    with physpix.World(gravity=(0, 100), **fields) as w:
        b = rect(w, 10, 10)
        w.step(0.1)
        assert b.velocity[1] == pytest.approx(10.0, rel=1e-3)


@pytest.mark.parametrize("name", ["fast", "balanced", "accurate"])
def test_from_preset_starts_from_the_preset_and_keywords_override_it(name):
    want = {"fast": (1, 10, 1), "balanced": (4, 20, 1), "accurate": (4, 80, 1)}[name]
    with physpix.World.from_preset(name, contact_erp=0.5) as w:
        s = w.settings
        assert (s["substeps"], s["solver_iterations"], s["raster_stride"]) == want
        assert s["contact_erp"] == 0.5 and s["continuous"] == 1
    with physpix.World.from_preset(physpix.Preset[name.upper()]) as w, physpix.World() as default:
        assert (w.settings == default.settings) == (name == "balanced")


def test_from_preset_refuses_an_unknown_name_or_field():
    with pytest.raises(ValueError, match="preset: 'quick' is not one of 'fast', 'balanced', 'accurate'"):
        physpix.World.from_preset("quick")
    with pytest.raises(TypeError, match="unexpected keyword argument 'substep'"):
        physpix.World.from_preset("fast", substep=3)


def test_a_bullet_stops_at_a_thin_wall_that_a_plain_body_passes():
    with physpix.World(gravity=(0, 0), allow_sleep=False, substeps=2) as w:
        wall = rect(w, 8, 200, position=(500, 100), density=100)
        plain = rect(w, 4, 4, position=(100, 60), linear_velocity=(5000, 0))
        bullet = rect(w, 4, 4, position=(100, 140), linear_velocity=(5000, 0), bullet=True)
        stops = 0
        for _ in range(30):
            w.step(1 / 60)
            stops += w.stats().swept_stops
        assert plain.position[0] > 1000
        assert bullet.position[0] < wall.position[0] and stops == 1


def test_properties_and_setters(space):
    b = rect(space, 20, 10, position=(50, 60), angle=0.25, linear_velocity=(3, 4), angular_velocity=0.5,
             user_data=0xDEADBEEF12345678)
    assert b.position == (50.0, 60.0)
    assert b.angle == pytest.approx(0.25)
    assert b.velocity == pytest.approx((3.0, 4.0), abs=1e-4)
    assert b.angular_velocity == pytest.approx(0.5, abs=1e-5)
    assert b.user_data == 0xDEADBEEF12345678
    assert b.size == (20, 10)
    b.position = (70, 80)
    assert b.position == (70.0, 80.0) and b.angle == pytest.approx(0.25)
    b.angle = -1.0
    assert b.position == (70.0, 80.0) and b.angle == pytest.approx(-1.0)
    b.velocity = (-5, 6)
    assert b.velocity == pytest.approx((-5.0, 6.0), abs=1e-4) and b.angular_velocity == pytest.approx(0.5, abs=1e-5)
    b.angular_velocity = 2.0
    assert b.velocity == pytest.approx((-5.0, 6.0), abs=1e-4) and b.angular_velocity == pytest.approx(2.0, abs=1e-5)


def test_impulse_changes_momentum_by_its_amount(space):
    b = rect(space, 10, 10, position=(100, 100))
    b.apply_impulse((500, 0), b.position)  # through the centre: no spin
    assert b.velocity == pytest.approx((500 / b.mass, 0.0), abs=1e-4)
    assert b.angular_velocity == pytest.approx(0.0, abs=1e-6)


def test_bodies_are_values(space):
    a = rect(space, 4, 4)
    b = rect(space, 4, 4, type=BodyType.KINEMATIC)
    assert space.bodies() == [a, b]
    assert len({a, b, *space.bodies()}) == 2
    assert a != b and a.world is space
    with physpix.World() as other:
        c = rect(other, 4, 4)
        assert c != a  # equality includes the world


def test_pivot_maps_bitmap_to_world(space):
    # custom pivot at the top-left corner: bitmap pixel (i, j) lies at position + (i, j) at angle 0.
    b = rect(space, 10, 10, position=(100, 100), custom_pivot=1, pivot=(0, 0))
    assert b.erase_circle((100.5, 100.5), 0.4) == 1
    mask = b.read_mask()
    assert mask[0, 0] == 0 and mask.sum() == 99


def test_sleeping_and_waking(world):
    rect(world, 800, 40, type="static", position=(400, 500))
    box = rect(world, 32, 32, position=(400, 464))
    for _ in range(120):
        world.step(1 / 60)
    assert not box.is_awake
    box.velocity = (0, -10)
    assert box.is_awake


def test_load_png_round_trip_and_body_from_sprite(tmp_path, space):
    rgba = np.zeros((6, 9, 4), dtype=np.uint8)
    rgba[..., 0] = np.arange(9) * 20
    rgba[..., 1] = np.arange(6)[:, None] * 30
    rgba[..., 2] = 7
    rgba[1:5, 2:8, 3] = 255  # a 6×4 opaque block
    path = tmp_path / "sprite.png"
    path.write_bytes(png_bytes(rgba))
    assert physpix.image_info(path) == (9, 6)
    loaded = physpix.load_png(str(path))
    assert loaded.dtype == np.uint8 and loaded.shape == (6, 9, 4)
    assert np.array_equal(loaded, rgba)
    body = space.create_body(rgba=loaded, density=2)
    assert body.mass == 2 * 24
    assert body.center_of_mass == pytest.approx((5.0, 3.0))
    gray = tmp_path / "gray.png"
    gray.write_bytes(png_bytes(np.full((3, 2), 77, dtype=np.uint8)))
    g = physpix.load_png(gray)
    assert g.shape == (3, 2, 4) and (g[..., :3] == 77).all() and (g[..., 3] == 255).all()


def test_log_hook_can_be_set_and_removed():
    physpix.set_log_hook(lambda level, msg: None)
    physpix.set_log_hook(None)


def test_stats_fields(world):
    rect(world, 10, 10)
    world.step(1 / 60)
    s = world.stats()
    assert s.bodies == 1 and s.awake_bodies == 1 and s.total_ms >= 0 and isinstance(s.backend, Backend)
    assert math.isfinite(s.solver_ms)


def test_worker_threads_and_memory():
    """Threads share the narrowphase without changing it; a body's memory counts a weight plane only when it has one."""
    finals = []
    for threads in (1, 2):
        with physpix.World(worker_threads=threads, allow_sleep=False) as w:
            # A pillar at the terrain's left end puts each box's whole square inside the terrain's bounds.
            terrain = np.zeros((300, 2000), np.uint8)
            terrain[260:, :] = terrain[:, :8] = 1
            w.create_body(mask=terrain, position=(1000, 570), type="static")
            boxes = [rect(w, 96, 96, position=(60 + 110 * i, 560 - 7 * (i % 5)), angle=0.1 * (i % 3)) for i in range(16)]
            used = 0
            for _ in range(40):
                w.step(1 / 60)
                used = max(used, w.stats().threads)
            assert used == threads
            finals.append([b.position for b in boxes])
    assert finals[0] == finals[1]
    with physpix.World() as w:
        plain = rect(w, 256, 256, type="static")
        weighted = rect(w, 256, 256, type="static", weights=np.full((256, 256), 9, np.uint8))
        assert weighted.memory[0] - plain.memory[0] == 256 * 256
        assert plain.memory[1] == 0 and 8 * plain.memory[0] / 256**2 < 1.5  # 1 bit a pixel, plus counts
