"""The same physics as the C tests: a resting box, the ground erased under it, analytic normals, splits."""
import math

import numpy as np
import pytest

import physpix
from physpix import BodyType, EventType
from pphelpers import angle_between_deg, rect, wrap_angle

DT = 1.0 / 60.0


def test_box_settles_on_ground_and_stays(world):
    # As tests/c/test_resting.c: ground 800×40 centred at (400, 500), its top at y = 480.
    ground = rect(world, 800, 40, type="static", position=(400, 500))
    box = rect(world, 32, 32, position=(400, 400))
    for _ in range(180):  # it lands after ~0.36 s; 3 s to settle
        world.step(DT)
    bottoms, angles, drift = [], [], []
    for _ in range(600):  # then 10 s, checked every step
        world.step(DT)
        x, y = box.position
        bottoms.append(y + 16.0)
        angles.append(abs(wrap_angle(box.angle)))
        drift.append(abs(x - 400.0))
    assert all(math.isfinite(v) for v in bottoms + angles)
    # The library leaves contact_slop (0.75 px) of penetration uncorrected: within 1 px of the top.
    assert max(abs(b - 480.0) for b in bottoms) <= 1.0, (min(bottoms), max(bottoms))
    assert math.degrees(max(angles)) <= 0.5
    assert max(drift) <= 2.0
    vx, vy = box.velocity
    assert abs(vx) + abs(vy) < 5.0
    contacts = world.collide(box, ground)
    assert contacts and all(c.a == box and c.b == ground for c in contacts)
    assert all(angle_between_deg(c.normal, (0, 1)) < 2.0 for c in contacts)


def test_a_box_falls_when_the_ground_under_it_is_erased(world):
    ground = rect(world, 800, 40, type="static", position=(400, 500))
    box = rect(world, 32, 32, position=(400, 464))
    for _ in range(240):
        world.step(DT)
    rest = box.position[1]
    assert rest == pytest.approx(464.0, abs=2.0)
    assert ground.erase_circle((400, 500), 60) > 3000
    assert box.is_awake, "the box resting on the edited ground must wake"
    for _ in range(5):
        world.step(DT)
    # Free fall for 5 steps at 980 px/s² is 0.5·980·(5/60)² ≈ 3.4 px.
    assert box.position[1] > rest + 2.0


def test_free_fall_follows_gravity(world):
    box = rect(world, 16, 16, position=(100, 100))
    for _ in range(30):
        world.step(DT)
    t = 30 * DT
    assert box.velocity[1] == pytest.approx(980.0 * t, rel=1e-3)
    assert box.position[1] - 100 == pytest.approx(0.5 * 980.0 * t * t, rel=0.05)
    assert box.position[0] == pytest.approx(100.0, abs=1e-3)


@pytest.mark.parametrize("mode", ["centroid", "manifold"])
def test_flat_overlap_has_the_analytic_normal_depth_and_count(mode):
    # As tests/c/test_normals.c: a 40×40 box sunk exactly 3 rows into the ground, overlap [480,520)×[500,503).
    with physpix.World(gravity=(0, 0), backend="cpu", contact_mode=mode) as w:
        ground = rect(w, 1000, 100, type=BodyType.STATIC, position=(500, 550))
        box = rect(w, 40, 40, position=(500, 483))
        contacts = w.collide(box, ground)
        assert len(contacts) == (1 if mode == "centroid" else 2)
        for c in contacts:
            assert c.pixel_count == 120
            assert angle_between_deg(c.normal, (0, 1)) < 0.5
            assert c.depth == pytest.approx(3.0, abs=0.5)
            assert 479.5 <= c.point[0] <= 520.5 and 499.5 <= c.point[1] <= 503.5
        if mode == "centroid":
            assert contacts[0].point == pytest.approx((500.0, 501.5), abs=0.5)
        swapped = w.collide(ground, box)
        assert swapped[0].a == ground and swapped[0].b == box
        assert angle_between_deg(swapped[0].normal, (0, -1)) < 0.5


@pytest.mark.parametrize("degrees", [0, 30, 45, 110])
def test_two_overlapping_boxes_touch_along_the_line_of_centres(space, degrees):
    # B sits 3 px into A's right face, both turned by the same angle: the normal is A's +x axis turned.
    th = math.radians(degrees)
    a = rect(space, 40, 40, position=(300, 300), angle=th)
    d = 40 - 3
    b = rect(space, 40, 40, position=(300 + d * math.cos(th), 300 + d * math.sin(th)), angle=th)
    world = space
    contacts = world.collide(a, b)
    assert contacts
    for c in contacts:
        assert angle_between_deg(c.normal, (math.cos(th), math.sin(th))) < 2.0
        assert c.depth == pytest.approx(3.0, abs=1.0)


def test_separated_bodies_have_no_contact(space):
    a = rect(space, 20, 20, position=(100, 100))
    b = rect(space, 20, 20, position=(125, 100))
    assert space.collide(a, b) == []


def test_contacts_after_a_step_name_the_pair(world):
    ground = rect(world, 800, 40, type="static", position=(400, 500))
    box = rect(world, 32, 32, position=(400, 466))  # 2 px into the ground
    world.step(DT)
    contacts = world.contacts()
    assert 1 <= len(contacts) <= 2
    for c in contacts:
        assert {c.a, c.b} == {box, ground}
        want = (0, 1) if c.a == box else (0, -1)
        assert angle_between_deg(c.normal, want) < 2.0
    stats = world.stats()
    assert stats.bodies == 2 and stats.contacts == len(contacts) and stats.backend == physpix.Backend.CPU


def test_head_on_collision_conserves_momentum(space):
    a = rect(space, 20, 20, position=(300, 300), linear_velocity=(300, 0))
    b = rect(space, 30, 30, position=(400, 300))
    p0 = a.mass * a.velocity[0] + b.mass * b.velocity[0]
    assert p0 == pytest.approx(120000.0, abs=1.0)
    for _ in range(60):
        space.step(DT)
    p1 = a.mass * a.velocity[0] + b.mass * b.velocity[0]
    assert b.velocity[0] > 50.0
    assert p1 == pytest.approx(p0, rel=0.01)


def test_cutting_a_bar_gives_a_split_event_with_the_new_body(space):
    bar = rect(space, 200, 8, position=(300, 300))
    m0 = bar.mass
    erased = bar.erase_circle((300, 300), 5)
    events = space.events()
    assert len(events) == 1
    ev = events[0]
    assert ev.type == EventType.BODY_SPLIT
    assert ev.body == bar, "the parent keeps its handle"
    assert isinstance(ev.other, physpix.Body) and ev.other != bar
    assert set(space.bodies()) == {bar, ev.other}
    assert bar.mass + ev.other.mass == pytest.approx(m0 - erased, abs=1e-3)
    # The halves are mirror images: equal mass, on either side of the cut.
    assert bar.mass == pytest.approx(ev.other.mass, abs=8.0)
    assert space.events() == [], "events are forgotten once read"


def test_erasing_every_pixel_destroys_the_body_with_an_event(space):
    b = rect(space, 20, 10, position=(100, 100))
    assert space.erase_circle((100, 100), 50) == 200
    events = space.events()
    assert [(e.type, e.body, e.other) for e in events] == [(EventType.BODY_DESTROYED, b, None)]
    assert space.bodies() == []
    with pytest.raises(physpix.InvalidHandleError):
        b.position


def test_many_events_are_all_read(space):
    bodies = [rect(space, 4, 4, position=(10 * i, 0)) for i in range(50)]
    assert space.bodies() == bodies
    for b in bodies:
        b.erase_circle(b.position, 10)
    events = space.events()
    assert [e.body for e in events] == bodies
    assert all(e.type == EventType.BODY_DESTROYED for e in events)


def test_gpu_backend_matches_the_cpu_or_is_unsupported():
    def pair_contacts(backend):
        with physpix.World(gravity=(0, 0), backend=backend) as w:
            a = w.create_body(mask=np.ones((40, 40)), position=(300, 300), angle=0.3)
            b = w.create_body(mask=np.ones((40, 40)), position=(334, 310), angle=-0.2)
            w.step(DT)
            return [(c.point, c.normal, c.depth, c.pixel_count) for c in w.collide(a, b)], w.stats().backend

    try:
        gpu, used = pair_contacts("gpu")
    except physpix.UnsupportedError as e:
        assert "glsl/" not in str(e), f"a shader of the project failed: {e}"  # a skip would hide the bug
        pytest.skip(f"no GPU backend here: {e}")
    cpu, _ = pair_contacts("cpu")
    assert used == physpix.Backend.GPU
    assert gpu == cpu


def test_a_split_piece_inherits_what_the_header_says(world):
    """include/physpix.h, 'What a split piece inherits': friction, restitution, gravity scale, user_data and
    type come along; the pivot is the piece's own centre, and the velocity that of the parent's material."""
    bar = rect(world, 200, 8, position=(300, 300), friction=0.25, restitution=0.5, user_data=77, custom_pivot=1,
               pivot=(10.0, 4.0))
    bar.gravity_scale = 0.5
    bar.velocity = (30.0, 0.0)
    bar.erase_circle((390.0, 300.0), 5)  # a 10 px piece off the right end
    (event,) = world.events()
    piece = event.other
    assert event.type == "body_split" and piece.type == "dynamic"
    assert (piece.friction, piece.restitution, piece.user_data) == (pytest.approx(0.25), pytest.approx(0.5), 77)
    assert piece.gravity_scale == pytest.approx(0.5)
    w, h = piece.size
    assert piece.pivot == (w / 2, h / 2) and bar.pivot == (10.0, 4.0)
    assert piece.velocity[0] == pytest.approx(30.0, abs=1e-3)
