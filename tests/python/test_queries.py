"""Issue 10 through Python: raycasts and point/box/circle queries, contact and sensor events, contact
impulses, sensors and one-way platforms, each checked against the physics it should follow."""
import math

import numpy as np
import pytest

import physpix
from physpix import EventType, InvalidArgumentError
from pphelpers import angle_between_deg, rect

DT = 1.0 / 60.0
G = 980.0


def ball(world, radius, **fields):
    """A solid disc of the given radius (px): the pixels whose centres lie within it."""
    size = 2 * radius
    y, x = np.mgrid[0:size, 0:size] + 0.5
    disc = (x - radius) ** 2 + (y - radius) ** 2 <= radius * radius
    return world.create_body(mask=disc, **fields)


# ---- raycasts ----

def test_a_ray_down_meets_a_static_box_on_its_top_face(space):
    # 100×40 centred at (300, 400): the top face is y = 380.
    box = rect(space, 100, 40, type="static", position=(300, 400))
    hit = space.raycast((310, 200), (310, 500))
    assert hit is not None and hit.body == box
    assert hit.point[0] == pytest.approx(310.0, abs=0.5) and hit.point[1] == pytest.approx(380.0, abs=0.5)
    assert angle_between_deg(hit.normal, (0, -1)) < 1.0
    assert math.hypot(*hit.normal) == pytest.approx(1.0, abs=1e-4)
    assert hit.fraction == pytest.approx((380.0 - 200.0) / 300.0, abs=0.5 / 300.0)


def test_a_ray_sideways_meets_the_left_face_and_the_nearest_body(space):
    rect(space, 20, 20, type="static", position=(400, 100))
    near = rect(space, 20, 20, type="static", position=(200, 100))  # left face x = 190
    hit = space.raycast((0, 103), (600, 103))
    assert hit.body == near
    assert hit.point == pytest.approx((190.0, 103.0), abs=0.5)
    assert angle_between_deg(hit.normal, (-1, 0)) < 1.0


def test_a_ray_that_meets_nothing_returns_none(space):
    rect(space, 100, 40, type="static", position=(300, 400))
    assert space.raycast((0, 0), (600, 0)) is None  # passes above
    assert space.raycast((300, 200), (300, 370)) is None  # stops 10 px short of the face


def test_a_ray_skips_bodies_its_mask_excludes_and_sensors(space):
    box = rect(space, 100, 40, type="static", position=(300, 400), category_bits=2)
    rect(space, 100, 20, type="static", position=(300, 300), is_sensor=True)  # on the way down, skipped
    assert space.raycast((300, 200), (300, 500), mask_bits=1) is None
    hit = space.raycast((300, 200), (300, 500), mask_bits=2)
    assert hit.body == box and hit.point[1] == pytest.approx(380.0, abs=0.5)


def test_a_ray_starting_inside_a_solid_pixel_hits_at_fraction_0(space):
    box = rect(space, 40, 40, type="static", position=(100, 100))
    hit = space.raycast((100, 100), (300, 100))
    assert hit.body == box and hit.fraction == 0.0
    assert hit.point == pytest.approx((100.0, 100.0), abs=0.5)
    assert angle_between_deg(hit.normal, (-1, 0)) < 1.0  # the ray's reverse


def test_raycast_refuses_a_mask_wider_than_32_bits(space):
    with pytest.raises(ValueError, match="mask_bits"):
        space.raycast((0, 0), (1, 1), mask_bits=2**32)


# ---- queries ----

def test_queries_find_the_bodies_with_solid_pixels_there(space):
    a = rect(space, 20, 20, type="static", position=(100, 100))  # spans 90..110
    b = rect(space, 20, 20, position=(200, 100))  # 190..210
    assert space.query_point((100.5, 100.5)) == [a]
    assert space.query_point((205, 95)) == [b]
    assert space.query_point((150, 100)) == []
    assert space.query_aabb((80, 80), (220, 120)) == [a, b]  # slot order
    assert space.query_aabb((105, 90), (195, 110)) == [a, b]
    assert space.query_aabb((115, 80), (185, 120)) == []
    assert space.query_circle((100, 100), 5) == [a]
    assert space.query_circle((150, 100), 45) == [a, b]
    assert space.query_circle((150, 100), 30) == []


def test_queries_leave_out_a_body_whose_pixels_there_were_erased(space):
    a = rect(space, 20, 20, type="static", position=(100, 100))
    b = rect(space, 20, 20, type="static", position=(130, 100))  # 120..140
    assert space.query_circle((110, 100), 12) == [a, b]
    assert a.erase_circle((100, 100), 6) > 100
    assert space.query_point((100.5, 100.5)) == []
    assert space.query_circle((100, 100), 3) == []
    assert space.query_aabb((97, 97), (103, 103)) == []  # every centre in it lies within 6 px of (100, 100)
    assert space.query_aabb((80, 80), (120, 120)) == [a]  # its other pixels are still there
    assert space.query_circle((110, 100), 12) == [a, b]


def test_queries_skip_sensors_and_follow_the_mask(space):
    a = rect(space, 20, 20, type="static", position=(100, 100), category_bits=4)
    rect(space, 20, 20, type="static", position=(100, 100), is_sensor=True)
    assert space.query_point((100.5, 100.5)) == [a]
    assert space.query_point((100.5, 100.5), mask_bits=4) == [a]
    assert space.query_point((100.5, 100.5), mask_bits=3) == []
    assert space.query_circle((100, 100), 5, mask_bits=~4 & 0xffffffff) == []


# ---- sensors ----

def test_a_ball_falls_through_a_sensor_which_reports_begin_then_end(world):
    sensor = rect(world, 200, 20, type="static", position=(300, 300), is_sensor=True)  # y 290..310
    b = ball(world, 8, position=(300, 200))  # bottom at 208
    events, begin_speed, fall_speed = [], None, None
    for n in range(1, 61):
        world.step(DT)
        for e in world.events():
            events.append(e)
            if e.type == EventType.SENSOR_BEGIN:
                begin_speed, fall_speed = e.approach_speed, b.velocity[1]
        # Unaffected by the sensor: free fall throughout, within 1 %.
        assert b.velocity[1] == pytest.approx(G * n * DT, rel=0.01)
        assert abs(b.velocity[0]) < 1e-3
    assert b.position[1] > 400, "the ball must fall through the sensor"
    sensor_events = [e for e in events if e.type in (EventType.SENSOR_BEGIN, EventType.SENSOR_END)]
    assert [e.type for e in sensor_events] == [EventType.SENSOR_BEGIN, EventType.SENSOR_END]
    assert all(e.body == sensor and e.other == b for e in sensor_events)
    assert not any(e.type in (EventType.CONTACT_BEGIN, EventType.CONTACT_END) for e in events), \
        "contact events are off by default"
    begin = sensor_events[0]
    assert begin.point[1] == pytest.approx(290.0, abs=8.0) and abs(begin.point[0] - 300) < 8
    assert angle_between_deg(begin.normal, (0, -1)) < 10.0  # from the sensor up to the ball
    # Nothing acts on a sensor pair: the closing speed is the ball's speed then (one step of gravity apart).
    assert begin_speed == pytest.approx(fall_speed, abs=G * DT + 1.0)
    assert sensor_events[1].point == (0.0, 0.0) and sensor_events[1].approach_speed == 0.0


# ---- contact events and impulses ----

def test_a_dropped_ball_reports_contact_begin_at_the_free_fall_speed():
    with physpix.World(backend="cpu", contact_events=True) as w:
        ground = rect(w, 400, 40, type="static", position=(300, 500))  # top y = 480
        h = 120.0
        b = ball(w, 8, position=(300, 480 - 8 - h), restitution=0)
        begins = []
        for _ in range(90):
            w.step(DT)
            begins += [e for e in w.events() if e.type == EventType.CONTACT_BEGIN]
        assert len(begins) == 1, begins
        e = begins[0]
        assert {e.body, e.other} == {b, ground}
        assert e.approach_speed == pytest.approx(math.sqrt(2 * G * h), rel=0.05)
        assert e.point[1] == pytest.approx(480.0, abs=2.0)
        down = (0, 1) if e.body == b else (0, -1)  # the normal points from body to other
        assert angle_between_deg(e.normal, down) < 5.0
        b.destroy()
        w.step(DT)
        ends = [e for e in w.events() if e.type == EventType.CONTACT_END]
        assert len(ends) == 1 and {ends[0].body, ends[0].other} == {b, ground}


def test_contact_events_switch_on_and_off_in_a_running_world():
    with physpix.World(backend="cpu", allow_sleep=False) as w:
        rect(w, 400, 40, type="static", position=(300, 500))
        ball(w, 8, position=(300, 400))
        assert w.contact_events is False
        for _ in range(60):
            w.step(DT)
        w.contact_events = True
        assert w.contact_events is True
        w.step(DT)
        begins = [e for e in w.events() if e.type == EventType.CONTACT_BEGIN]
        assert len(begins) == 1, "the pair already touching begins when events go on"
        w.contact_events = False
        for _ in range(10):
            w.step(DT)
        assert not w.events()


def test_no_contact_events_without_contact_events():
    with physpix.World(backend="cpu", allow_sleep=False) as w:
        rect(w, 400, 40, type="static", position=(300, 500))
        ball(w, 8, position=(300, 400))
        for _ in range(60):
            w.step(DT)
        assert w.contacts(), "the ball must be touching the ground"
        assert not [e for e in w.events() if e.type in (EventType.CONTACT_BEGIN, EventType.CONTACT_END)]


def test_a_resting_box_is_held_by_its_weight_in_normal_impulses():
    with physpix.World(backend="cpu", allow_sleep=False) as w:
        rect(w, 800, 40, type="static", position=(400, 500))
        box = rect(w, 32, 32, position=(400, 463), density=2.0)
        for _ in range(180):
            w.step(DT)
        h = DT / w.settings["substeps"]
        sums = []
        for _ in range(60):
            w.step(DT)
            cs = w.contacts()
            assert cs and all(c.normal_impulse >= 0 for c in cs)
            sums.append(sum(c.normal_impulse for c in cs))
        assert np.mean(sums) == pytest.approx(box.mass * G * h, rel=0.02)
        # collide() runs no solver: its impulses are zero.
        assert all(c.normal_impulse == 0 for c in w.collide(box, w.bodies()[0]))


# ---- one-way platforms ----

def _launch_under_platform(one_way):
    """A 16 px box launched up from below a 10 px platform (top y = 295) fast enough to rise 200 px;
    returns (lowest y reached above the platform, final y, final velocity)."""
    with physpix.World(backend="cpu") as w:
        rect(w, 200, 10, type="static", position=(300, 300), one_way=one_way)
        box = rect(w, 16, 16, position=(300, 400), fixed_rotation=True,
                   linear_velocity=(0, -math.sqrt(2 * G * 200)))
        top = 400.0
        for _ in range(300):
            w.step(DT)
            top = min(top, box.position[1])
        return top, box.position[1], box.velocity


def test_a_body_passes_up_through_a_one_way_platform_and_lands_on_it():
    top, y, v = _launch_under_platform(True)
    assert top < 295 - 8 - 50, "it must pass through and rise well above the platform"
    assert y == pytest.approx(295 - 8, abs=1.5), "it must end resting on the platform's top"
    assert math.hypot(*v) < 5.0


def test_a_plain_platform_stops_the_same_body_from_below():
    top, y, _ = _launch_under_platform(False)
    assert top > 305, "it must stay below the platform's underside (y = 305)"
    assert y > 305


def test_one_way_refuses_a_zero_direction(space):
    with pytest.raises(InvalidArgumentError, match="one_way_direction"):
        rect(space, 10, 10, type="static", one_way=True, one_way_direction=(0, 0))
    default = physpix._native.lib.pp_body_def_default()
    assert (default.one_way_direction.x, default.one_way_direction.y) == (0.0, -1.0)


# ---- explosions and casts (issue 44) ----

def test_explode_pushes_by_the_extent_across_the_blast_and_casts_stop_where_bodies_touch(space):
    # Extents 16 and 48 px across a blast from (200, 200), both faces 20 px away: impulses 16 and 48 × 10.
    a = rect(space, 16, 16, position=(228, 200))
    b = rect(space, 16, 48, position=(172, 200))
    assert space.explode((200, 200), 50, falloff=40, impulse_per_length=10) == 0
    assert a.mass * a.velocity[0] == pytest.approx(160, rel=1e-4)
    assert b.mass * b.velocity[0] == pytest.approx(-480, rel=1e-4)
    with pytest.raises(InvalidArgumentError):
        space.explode((200, 200), -1)
    # A box 70 px over a static slab stops on it, the slab's normal up; nothing lies above it.
    ground = rect(space, 100, 40, type="static", position=(500, 300))
    box = rect(space, 20, 20, position=(500, 200))
    hit = space.cast_body(box, (0, 100))
    assert hit.body == ground and hit.fraction * 100 == pytest.approx(70, abs=1 / 16)
    assert hit.normal == pytest.approx((0, -1), abs=1e-6)
    assert space.cast_body(box, (0, -100)) is None
    # A ray through the three boxes, nearest first.
    hits = space.raycast_all((0, 200), (600, 200))
    assert [h.body for h in hits] == [b, a, box]
    assert [h.fraction for h in hits] == sorted(h.fraction for h in hits)
