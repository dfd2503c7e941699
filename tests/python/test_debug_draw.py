"""World.debug_draw: a numpy structured array of segments (a box is its 4 outline edges at its world corners),
the view box, flags and misuse; Joint.anchors."""
import numpy as np
import pytest

import physpix
from physpix import DebugKind, InvalidArgumentError
from pphelpers import raises_from_library, rect


def test_a_box_is_four_outline_segments_at_its_corners(space):
    box = rect(space, 16, 16, position=(100, 50))  # the pivot is the centre: 92..108 × 42..58
    segs = space.debug_draw(physpix.DEBUG_DRAW_OUTLINES)
    assert segs.dtype.names == ("a", "b", "rgba", "kind", "body")
    assert segs.shape == (4,) and segs["a"].shape == (4, 2) and segs["b"].shape == (4, 2)
    assert set(segs["kind"]) == {DebugKind.OUTLINE} and set(segs["body"]) == {box.id}
    assert set(segs["rgba"]) == {0xE5B2B2FF}, "an awake dynamic body is pink"
    edges = {(tuple(a), tuple(b)) for a, b in zip(segs["a"].tolist(), segs["b"].tolist())}
    assert edges == {((92, 42), (108, 42)), ((108, 42), (108, 58)), ((108, 58), (92, 58)), ((92, 58), (92, 42))}


def test_every_flag_by_default_and_the_view_box_culls(space):
    rect(space, 16, 16, position=(100, 50))
    far = rect(space, 16, 16, position=(1000, 50), type="static")
    segs = space.debug_draw()
    assert len(segs) == (4 + 4 + 2 + 1) + (4 + 4 + 2)
    kinds = segs["kind"].tolist()
    assert kinds.count(DebugKind.OUTLINE) == 8 and kinds.count(DebugKind.AABB) == 8
    assert kinds.count(DebugKind.CENTER) == 4 and kinds.count(DebugKind.VELOCITY) == 1
    near = space.debug_draw(lower=(900, 0), upper=(1100, 100))
    assert len(near) == 4 + 4 + 2 and set(near["body"]) == {far.id}
    assert len(space.debug_draw(lower=(-50, -50), upper=(-10, -10))) == 0


def test_contacts_are_drawn_at_the_reported_points(world):
    rect(world, 200, 20, type="static", position=(100, 110))
    rect(world, 20, 20, position=(100, 91))
    world.step(1 / 60)
    contacts = world.contacts()
    segs = world.debug_draw(physpix.DEBUG_DRAW_CONTACTS)
    assert len(contacts) > 0 and len(segs) == 3 * len(contacts)
    for i, c in enumerate(contacts):
        cross = segs[3 * i]
        assert cross["kind"] == DebugKind.CONTACT
        assert np.allclose((cross["a"] + cross["b"]) / 2, c.point, atol=1e-4)
        assert np.allclose(segs[3 * i + 2]["a"], c.point) and segs[3 * i + 2]["kind"] == DebugKind.NORMAL


def test_joint_anchors_and_their_segments(world):
    rod = rect(world, 10, 60, position=(200, 200))
    hinge = world.create_joint("revolute", body_b=rod, anchor_a=(200, 175))
    assert hinge.anchors[0] == (200, 175) and np.allclose(hinge.anchors[1], (200, 175), atol=1e-4)
    segs = world.debug_draw(physpix.DEBUG_DRAW_JOINTS)
    assert len(segs) == 2 and set(segs["kind"]) == {DebugKind.JOINT}
    assert tuple(segs["a"][0]) == hinge.anchors[0] and np.allclose(segs["a"][1], rod.position, atol=1e-3)


def test_misuse_raises_with_the_library_message(space):
    rect(space, 8, 8)
    raises_from_library(InvalidArgumentError, ["flags"], space.debug_draw, 1 << 6)
    raises_from_library(InvalidArgumentError, ["lower"], space.debug_draw, lower=(10, 10), upper=(0, 0))
    raises_from_library(InvalidArgumentError, ["finite"], space.debug_draw, lower=(float("nan"), 0), upper=(1, 1))
    with pytest.raises(ValueError):
        space.debug_draw(-1)
