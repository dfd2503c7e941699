"""Enums compare as written and print as names; errors name the package's call the program made, not the C function
behind it."""
import numpy as np
import pytest

import physpix
from physpix import BodyType, EventType, JointType, Status
from pphelpers import rect


def test_body_type_equals_its_name_its_member_and_its_value(world):
    box = rect(world, 8, 8)
    assert box.type == "dynamic" and box.type == BodyType.DYNAMIC and box.type == 0
    assert box.type != "static" and not box.type == "static" and box.type != BodyType.STATIC
    assert not box.type != "dynamic"
    box.type = "kinematic"
    assert box.type == "kinematic" and box.type == BodyType.KINEMATIC and box.type == 2 and box.type != "dynamic"
    assert box.type == "Kinematic", "names are case-insensitive, as the package takes them"


def test_a_blast_loop_written_with_names_pushes_the_dynamic_bodies(world):
    ground = rect(world, 200, 10, type="static", position=(100, 300))
    crates = [rect(world, 8, 8, position=(60 + 40 * i, 280)) for i in range(3)]
    pushed = [b for b in world.bodies() if b.type == "dynamic"]
    assert pushed == crates and ground not in pushed
    for b in pushed:
        b.apply_impulse((0.0, -100.0 * b.mass), b.position)
    world.step(1 / 60)
    assert all(b.velocity[1] < -50 for b in crates) and ground.velocity == (0.0, 0.0)


def test_event_types_compare_and_print_as_names(space):
    bar = rect(space, 200, 8, position=(300, 300))
    bar.erase_circle((300, 300), 5)
    (event,) = space.events()
    assert event.type == "body_split" and event.type == EventType.BODY_SPLIT and event.type == 1
    assert event.type != "body_destroyed"
    assert str(event.type) == "body_split" and f"{event.type}" == "body_split" and f"{event.type:>12}" == "  body_split"
    assert f"{event.type:d}" == "1" and int(event.type) == 1
    assert repr(event.type) == "<EventType.BODY_SPLIT: 1>"
    assert "type=<EventType.BODY_SPLIT: 1>" in repr(event)


def test_joint_types_compare_as_names(world):
    rod = rect(world, 40, 4, position=(100, 100))
    joint = world.create_joint("revolute", body_b=rod, anchor_a=(80, 100))
    assert joint.type == "revolute" and joint.type == JointType.REVOLUTE and joint.type != "weld"
    assert str(joint.type) == "revolute"


def test_members_still_behave_as_ints():
    assert {BodyType.STATIC: "s"}[1] == "s" and {1: "s"}[BodyType.STATIC] == "s"
    assert BodyType.KINEMATIC > BodyType.DYNAMIC and BodyType.STATIC + 1 == 2
    assert BodyType(1) is BodyType.STATIC
    assert BodyType.DYNAMIC != None and BodyType.DYNAMIC != 0.5 and BodyType.DYNAMIC == 0.0  # noqa: E711
    assert str(Status.INVALID_ARGUMENT) == "invalid_argument"


@pytest.mark.parametrize("call, make", [
    ("load_png", lambda tmp: physpix.load_png(tmp / "missing.png")),
    ("image_info", lambda tmp: physpix.image_info(tmp / "missing.png")),
    ("save_png", lambda tmp: physpix.save_png(tmp / "no" / "such" / "x.png", np.zeros((2, 2, 4), np.uint8))),
    ("World.load_scene", lambda tmp: physpix.World.load_scene(tmp / "missing.json")),
    ("World", lambda tmp: physpix.World(gravity=(float("nan"), 0.0))),
])
def test_errors_name_the_python_call(tmp_path, call, make):
    with pytest.raises(physpix.PhysPixError) as info:
        make(tmp_path)
    e = info.value
    assert e.call == call and str(e).startswith(call + ": "), str(e)
    assert "pp_" not in str(e), "the message names the C function"
    assert e.function.startswith("pp_") and e.library_message.startswith(e.function + ": ")
    assert str(e)[len(call):] == e.library_message[len(e.function):], "the library's text follows the call's name"


def test_method_and_property_errors_name_class_and_member(world):
    box = rect(world, 8, 8)
    with pytest.raises(physpix.InvalidArgumentError, match=r"^World\.step: dt must be finite"):
        world.step(-1.0)
    with pytest.raises(physpix.InvalidArgumentError, match=r"^Body\.erase_circle: radius"):
        box.erase_circle((0, 0), -1.0)
    box.destroy()
    with pytest.raises(physpix.InvalidHandleError, match=r"^Body\.position: body handle"):
        box.position
