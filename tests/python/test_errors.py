"""Every error path raises its PhysPixError subclass carrying the library's own message."""
import math

import numpy as np
import pytest

import physpix
from physpix import Status, _native
from pphelpers import png_bytes, raises_from_library, rect


@pytest.mark.parametrize("dt", [math.nan, math.inf, -1 / 60, 0.0, 1.5])
def test_bad_dt_is_invalid_argument_naming_dt(world, dt):
    box = rect(world, 8, 8, position=(100, 100))
    e = raises_from_library(physpix.InvalidArgumentError, ["dt"], world.step, dt)
    assert e.function == "pp_world_step"
    assert box.position == (100.0, 100.0), "a refused step moved the body"


def test_destroyed_body_is_an_invalid_handle(world):
    b = rect(world, 8, 8)
    keep = rect(world, 8, 8)
    b.destroy()
    raises_from_library(physpix.InvalidHandleError, ["body", "handle"], lambda: b.position)
    raises_from_library(physpix.InvalidHandleError, ["body", "handle"], b.erase_circle, (0, 0), 4)
    raises_from_library(physpix.InvalidHandleError, ["body", "handle"], b.destroy)
    raises_from_library(physpix.InvalidHandleError, ["body", "handle"], world.collide, b, keep)
    assert world.bodies() == [keep]


def test_a_body_of_another_world_is_an_invalid_handle(world):
    with physpix.World() as other:
        theirs, ours = rect(other, 8, 8), rect(world, 8, 8)
        raises_from_library(physpix.InvalidHandleError, ["belongs to world"], world.collide, theirs, ours)
        raises_from_library(physpix.InvalidHandleError, ["belongs to world"], world.schedule_paint, 1.0, theirs,
                            (0, 0), 2)
        assert world.scheduled_edits() == [] and theirs.position == (0.0, 0.0)


def test_a_joint_handle_is_not_a_body_and_a_body_handle_is_not_a_joint(world):
    # The world's first body and first joint share slot 0: before handles carried their kind they had one id, and
    # Joint(world, body.id).destroy() removed the joint.
    box = rect(world, 16, 16, position=(100, 100))
    hinge = world.create_joint("revolute", body_b=box, anchor_a=(100, 92))
    box_as_joint, hinge_as_body = physpix.Joint(world, box.id), physpix.Body(world, hinge.id)
    raises_from_library(physpix.InvalidHandleError, ["is a body handle, not a joint"], box_as_joint.destroy)
    raises_from_library(physpix.InvalidHandleError, ["is a body handle, not a joint"], lambda: box_as_joint.value)
    raises_from_library(physpix.InvalidHandleError, ["is a joint handle, not a body"], hinge_as_body.destroy)
    raises_from_library(physpix.InvalidHandleError, ["is a joint handle, not a body"], lambda: hinge_as_body.position)
    raises_from_library(physpix.InvalidHandleError, ["is a joint handle, not a body"], world.create_joint,
                        "revolute", body_b=hinge_as_body, anchor_a=(100, 92))
    assert world.bodies() == [box] and world.joints() == [hinge]


def test_context_manager_destroys_the_world():
    with physpix.World() as w:
        b = rect(w, 8, 8)
    raises_from_library(physpix.InvalidHandleError, ["world", "handle"], lambda: b.position)
    raises_from_library(physpix.InvalidHandleError, ["world", "handle"], w.step, 1 / 60)
    raises_from_library(physpix.InvalidHandleError, ["world", "handle"], w.create_body, mask=np.ones((2, 2)))
    w.close()  # closing twice is harmless


def test_a_world_left_to_the_garbage_collector_is_destroyed():
    w = physpix.World()
    handle = _native.pp_world(w.id)
    del w
    raises_from_library(physpix.InvalidHandleError, ["world"], _native.lib.pp_world_step, handle, 1 / 60)


def test_wrong_struct_size_is_an_abi_error(world):
    raises_from_library(physpix.AbiError, ["struct_size"], physpix.World, struct_size=8)
    raises_from_library(physpix.AbiError, ["struct_size"], world.create_body, mask=np.ones((2, 2)), struct_size=8)


def test_oversized_bitmap_is_a_limit_error(world):
    raises_from_library(physpix.LimitError, ["width"], world.create_body, mask=np.ones((1, 16385), dtype=np.uint8))


def test_library_refusals_through_create_and_edits(world):
    raises_from_library(physpix.InvalidArgumentError, ["solid", "mass", "pixel", "empty"],
                        world.create_body, mask=np.zeros((4, 4)))
    raises_from_library(physpix.InvalidArgumentError, ["position"], world.create_body, mask=np.ones((4, 4)),
                        position=(math.nan, 0))
    raises_from_library(physpix.InvalidArgumentError, ["density"], world.create_body, mask=np.ones((4, 4)),
                        density=-1)
    b = rect(world, 20, 10)
    raises_from_library(physpix.InvalidArgumentError, ["radius"], b.erase_circle, (0, 0), -1)
    raises_from_library(physpix.InvalidArgumentError, ["weight"], b.paint_circle, (0, 0), 3, weight=0)
    raises_from_library(physpix.InvalidArgumentError, ["outside"], b.write_pixels, 20, 0, np.ones((2, 2)))
    raises_from_library(physpix.InvalidArgumentError, ["angle"], b.set_transform, (0, 0), math.nan)
    static = rect(world, 10, 10, type="static")
    raises_from_library(physpix.InvalidArgumentError, ["dynamic", "static"], static.apply_impulse, (1, 0), (0, 0))


def test_inconsistent_arrays_are_value_errors_before_the_library(world):
    with pytest.raises(ValueError, match="disagree"):
        world.create_body(mask=np.ones((4, 4)), weights=np.ones((4, 5), dtype=np.uint8))
    with pytest.raises(ValueError, match="disagree"):
        world.create_body(mask=np.ones((4, 4)), rgba=np.zeros((5, 4, 4), dtype=np.uint8))
    with pytest.raises(ValueError, match="shape"):
        world.create_body(rgba=np.zeros((4, 4, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="shape"):
        world.create_body(mask=np.ones(16))
    with pytest.raises(ValueError, match="0..255"):
        world.create_body(mask=np.ones((2, 2)), weights=np.full((2, 2), 300))
    with pytest.raises(ValueError):
        world.create_body()
    b = rect(world, 8, 8)
    with pytest.raises(ValueError, match="shape"):
        b.write_pixels(0, 0, np.ones((2, 2)), weights=np.ones((2, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="weight"):
        b.paint_circle((0, 0), 2, weight=256)
    assert world.bodies() == [b]


def test_unknown_keywords_and_enum_names():
    with pytest.raises(TypeError, match="gravityy"):
        physpix.World(gravityy=(0, 1))
    with pytest.raises(ValueError) as info:
        physpix.World(backend="tpu")
    assert all(name in str(info.value) for name in ("'auto'", "'cpu'", "'gpu'"))
    with pytest.raises(ValueError, match="area_gradient"):
        physpix.World(normal_method=7)
    with pytest.raises(TypeError, match="gravity"):
        physpix.World(gravity=5)
    with pytest.raises(TypeError, match="contact_slop"):
        physpix.World(contact_slop="loose")
    with physpix.World() as w:
        with pytest.raises(TypeError, match="densty"):
            w.create_body(mask=np.ones((2, 2)), densty=1)
        with pytest.raises(TypeError, match="width"):
            w.create_body(mask=np.ones((2, 2)), width=2)
        with pytest.raises(ValueError, match="kinematic"):
            w.create_body(mask=np.ones((2, 2)), type="floating")


def test_png_errors(tmp_path):
    missing = tmp_path / "missing.png"
    raises_from_library(physpix.PhysPixIOError, ["cannot open"], physpix.load_png, missing)
    corrupt = tmp_path / "corrupt.png"
    corrupt.write_bytes(b"GIF89a not a png")
    raises_from_library(physpix.FormatError, ["signature"], physpix.load_png, corrupt)
    truncated = tmp_path / "truncated.png"
    truncated.write_bytes(png_bytes(np.full((8, 8, 4), 200, dtype=np.uint8))[:-20])
    e = raises_from_library(physpix.FormatError, [str(truncated)], physpix.load_png, truncated)
    huge = tmp_path / "huge.png"
    huge.write_bytes(png_bytes(np.zeros((1, 16385), dtype=np.uint8)))
    raises_from_library(physpix.LimitError, ["PP_MAX_BITMAP_SIDE"], physpix.load_png, huge)
    assert e.function == "pp_image_load"


def test_one_exception_class_per_status():
    classes = {s: physpix.errors.error_for(s, "m", "f", "n") for s in Status if s != Status.OK}
    assert {type(e) for e in classes.values()} == {
        physpix.InvalidArgumentError, physpix.InvalidHandleError, physpix.OutOfMemoryError, physpix.PhysPixIOError,
        physpix.FormatError, physpix.UnsupportedError, physpix.LimitError, physpix.AbiError}
    for status, e in classes.items():
        assert isinstance(e, physpix.PhysPixError) and e.status == status
        assert _native.status_name(status) == "PP_ERR_" + status.name
    unknown = physpix.errors.error_for(99, "", "pp_x", "PP_ERR_?")
    assert type(unknown) is physpix.PhysPixError and unknown.status == 99 and "pp_x" in unknown.message
