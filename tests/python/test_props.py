"""Runtime properties from Python: the world's gravity, every body's state in one call, sleep set by hand,
damping and filters (the same physics as tests/c/test_props.c)."""
import math

import numpy as np
import pytest

import physpix
from pphelpers import raises_from_library, rect

DT = 1.0 / 60.0


def test_gravity_set_mid_fall_changes_the_acceleration(world):
    box = rect(world, 16, 16, position=(400, -3000))
    for _ in range(6):
        world.step(DT)
    v0 = box.velocity[1]
    world.gravity = (0, 490)
    assert world.gravity == (0.0, 490.0)
    for _ in range(60):
        world.step(DT)
    assert box.velocity[1] - v0 == pytest.approx(490.0, abs=0.01)
    raises_from_library(physpix.InvalidArgumentError, ["finite"], setattr, world, "gravity", (math.nan, 0))
    assert world.gravity == (0.0, 490.0)


def test_body_states_are_one_structured_array_matching_the_properties(world):
    rect(world, 800, 40, type="static", position=(400, 500))
    boxes = [rect(world, 16, 16, position=(300 + 40 * i, 300), angle=0.1 * i) for i in range(3)]
    for _ in range(20):
        world.step(DT)
    s = world.body_states()
    assert s.dtype.names == ("body", "position", "angle", "linear_velocity", "angular_velocity", "awake", "user_data")
    assert len(s) == 4 and [int(i) for i in s["body"]] == [b.id for b in world.bodies()]
    for row, box in zip(s[1:], boxes):
        assert tuple(row["position"]) == pytest.approx(box.position, abs=0)
        assert row["angle"] == pytest.approx(box.angle, abs=0)
        assert tuple(row["linear_velocity"]) == pytest.approx(box.velocity, abs=0)
        assert row["angular_velocity"] == pytest.approx(box.angular_velocity, abs=0)
        assert bool(row["awake"]) == box.is_awake
    assert not s["awake"][0] and tuple(s["linear_velocity"][0]) == (0, 0)  # the static ground


def test_body_states_carry_user_data_and_world_body_turns_an_id_back_into_its_body(world):
    big = 0xFEEDFACE12345678  # above 2^63: the field is unsigned
    tagged, plain = rect(world, 16, 16, position=(300, 300), user_data=big), rect(world, 16, 16, position=(340, 300))
    s = world.body_states()
    assert [int(u) for u in s["user_data"]] == [big, 0]
    found = world.body(int(s["body"][0]))
    assert found == tagged and found.user_data == big and world.body(plain.id) == plain
    other = physpix.World()
    try:
        foreign = rect(other, 16, 16).id
        raises_from_library(physpix.InvalidHandleError, ["World.body"], world.body, foreign)
    finally:
        other.close()
    plain.destroy()
    raises_from_library(physpix.InvalidHandleError, ["World.body"], world.body, plain.id)
    with pytest.raises(physpix.IntegerRangeError):
        world.body(-1)


def test_a_box_put_to_sleep_in_the_air_hangs_then_falls_when_woken(world):
    box = rect(world, 16, 16, position=(400, 200))
    for _ in range(10):
        world.step(DT)
    box.awake = False
    assert not box.awake
    hung = box.position
    for _ in range(30):
        world.step(DT)
    assert box.position == hung
    box.awake = True
    for _ in range(30):
        world.step(DT)
    n, h = 120, DT / 4  # 30 steps of 4 substeps from rest: g·h²·n(n+1)/2
    assert box.position[1] - hung[1] == pytest.approx(980 * h * h * n * (n + 1) / 2, abs=0.05)


def test_a_filter_that_drops_the_ground_lets_a_resting_box_fall_through(world):
    rect(world, 800, 40, type="static", position=(400, 500))
    box = rect(world, 16, 16, position=(400, 472))
    for _ in range(120):
        world.step(DT)
    y0 = box.position[1]
    box.set_filter(1, 0)
    for _ in range(30):
        world.step(DT)
    assert box.position[1] - y0 > 100
    with pytest.raises(physpix.IntegerRangeError, match=r"category_bits: -1 is outside uint32"):
        box.set_filter(-1, 0)


def test_damping_slows_a_thrown_box_and_bad_damping_is_refused(world):
    world.gravity = (0, 0)
    free, damped = rect(world, 16, 16, position=(100, 100)), rect(world, 16, 16, position=(100, 300))
    for b in (free, damped):
        b.velocity = (100, 0)
    damped.set_damping(0.5, 0)  # 1/s: a second leaves e^-0.5 of the speed
    for _ in range(60):
        world.step(DT)
    assert free.velocity[0] == pytest.approx(100)
    assert damped.velocity[0] == pytest.approx(100 * math.exp(-0.5), rel=1e-3)
    raises_from_library(physpix.InvalidArgumentError, ["damping"], damped.set_damping, -1, 0)


def test_a_force_for_one_step_gives_f_dt_and_a_torque_tau_dt(world):
    world.gravity = (0, 0)
    box = rect(world, 16, 16, position=(400, 300))
    box.apply_force((600 * box.mass, 0), box.position)
    box.apply_torque(3 * box.inertia)
    world.step(DT)
    assert box.velocity[0] == pytest.approx(600 * DT, abs=1e-4)
    assert box.angular_velocity == pytest.approx(3 * DT, abs=1e-5)
    world.step(DT)
    assert box.velocity[0] == pytest.approx(600 * DT, abs=1e-4)  # spent
    w0 = box.angular_velocity
    box.apply_angular_impulse(2 * box.inertia)
    assert box.angular_velocity - w0 == pytest.approx(2.0, abs=1e-5)
    raises_from_library(physpix.InvalidArgumentError, ["finite"], box.apply_torque, math.nan)


def test_friction_restitution_density_and_gravity_scale_are_settable_properties(world):
    box = rect(world, 16, 16, position=(400, 1000))
    assert (box.friction, box.restitution, box.density, box.gravity_scale) == (pytest.approx(0.6), 0.0, 1.0, 1.0)
    m = box.mass
    box.friction, box.restitution, box.density, box.gravity_scale = 0.25, 0.5, 3.0, 0.0
    assert (box.friction, box.restitution, box.density, box.gravity_scale) == (0.25, 0.5, 3.0, 0.0)
    assert box.mass == pytest.approx(3 * m)
    y = box.position[1]
    for _ in range(30):
        world.step(DT)
    assert box.position[1] == y  # gravity scale 0: it floats
    raises_from_library(physpix.InvalidArgumentError, ["restitution"], setattr, box, "restitution", 2.0)
    assert box.restitution == 0.5


def test_type_and_fixed_rotation_set_from_python(world):
    shelf = rect(world, 64, 8, position=(400, 300), type="static")
    box = rect(world, 16, 16, position=(400, 200))
    assert shelf.type == physpix.BodyType.STATIC
    shelf.type = "dynamic"
    assert shelf.type == physpix.BodyType.DYNAMIC and shelf.mass == pytest.approx(512)
    y0 = shelf.position[1]
    for _ in range(30):
        world.step(DT)
    assert shelf.position[1] - y0 == pytest.approx(0.5 * 980 * 0.5 ** 2, rel=0.03)  # it falls as g says
    box.type = physpix.BodyType.KINEMATIC
    box.velocity = (10, 0)
    box.fixed_rotation = True
    assert box.fixed_rotation
    for _ in range(60):
        world.step(DT)
    assert box.velocity == pytest.approx((10, 0))  # no gravity on a kinematic body
    with pytest.raises(ValueError, match="type"):
        box.type = "floating"
