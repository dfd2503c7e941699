"""Integers reach C unwrapped and paths uncut: ctypes wraps an int into its C type silently (2**32 + 5 into a uint32
is 5) and a C string ends at its first NUL, so the package refuses both before the library is called. The def
structs' cases come from their ctypes _fields_, so a new integer field is covered without a new line here."""
import ctypes
import os
from pathlib import Path

import numpy as np
import pytest

import physpix
from physpix import Body, World, _native
from physpix.world import _ENUM_FIELDS
from pphelpers import raises_from_library, rect


def c_range(ctype):
    """(name, low, high) of a ctypes integer type: ("uint32", 0, 4294967295)."""
    bits = 8 * ctypes.sizeof(ctype)
    if ctype(-1).value < 0:
        return f"int{bits}", -2 ** (bits - 1), 2 ** (bits - 1) - 1
    return f"uint{bits}", 0, 2 ** bits - 1


def range_message(name, value, ctype):
    kind, low, high = c_range(ctype)
    return f"{name}: {value} is outside {kind} [{low}, {high}]"


def is_c_int(ctype):
    return isinstance(ctype, type) and issubclass(ctype, ctypes._SimpleCData) and ctype._type_ in "bBhHiIlLqQ"


# caller: (def struct, the C call it reaches, integer fields set from the arrays rather than keywords)
DEFS = {"World": (_native.pp_world_def, "pp_world_create", ()),
        "create_body": (_native.pp_body_def, "pp_body_create", ("width", "height"))}


def int_fields(caller):
    struct, _, skip = DEFS[caller]
    return [(name, ctype) for name, ctype in struct._fields_ if is_c_int(ctype) and name not in skip]


def field_cases(enums):
    """pytest params (caller, name, ctype) for each integer field, the enum fields or the others."""
    return [pytest.param(caller, name, ctype, id=f"{caller}-{name}") for caller in DEFS
            for name, ctype in int_fields(caller) if (name in _ENUM_FIELDS) == enums]


def create(world, caller, **fields):
    if caller == "World":
        return World(**fields)
    return world.create_body(mask=np.ones((2, 2), dtype=np.uint8), **fields)


class Reached(Exception):
    """Raised by the spy in place of the C call: the def struct got that far."""


def def_reaching_c(monkeypatch, world, caller, **fields):
    """The def struct create() hands to the C call, caught by a spy standing in for the call."""
    struct, fn_name, _ = DEFS[caller]
    seen = []

    def spy(*args):
        seen.extend(struct.from_buffer_copy(a._obj) for a in args if isinstance(getattr(a, "_obj", None), struct))
        raise Reached

    monkeypatch.setattr(_native.lib, fn_name, spy)
    with pytest.raises(Reached):
        create(world, caller, **fields)
    monkeypatch.undo()
    assert len(seen) == 1
    return seen[0]


# ---- the two findings of issue 26 (7) ----

def test_write_pixels_at_2_to_the_32_is_refused_not_written_at_x_0(world):
    body = rect(world, 8, 8)
    with pytest.raises(OverflowError) as info:
        body.write_pixels(2**32, 0, np.zeros((2, 2)))
    assert str(info.value) == "x: 4294967296 is outside int32 [-2147483648, 2147483647]"
    assert body.read_mask().all(), "a refused write changed the mask"


def test_category_bits_2_to_the_32_plus_5_is_refused_not_stored_as_5(world):
    with pytest.raises(OverflowError) as info:
        rect(world, 4, 4, category_bits=2**32 + 5)
    assert str(info.value) == "category_bits: 4294967301 is outside uint32 [0, 4294967295]"
    assert isinstance(info.value, physpix.IntegerRangeError) and isinstance(info.value, ValueError)
    assert world.bodies() == []


# ---- every integer field of pp_world_def and pp_body_def ----

def test_the_field_cases_cover_the_structs():
    names = {caller: {name for name, _ in int_fields(caller)} for caller in DEFS}
    assert {"struct_size", "substeps", "exact_solver", "backend", "worker_threads", "contact_events"} <= names["World"]
    assert {"struct_size", "type", "category_bits", "mask_bits", "user_data", "is_sensor"} <= names["create_body"]
    assert not names["create_body"] & {"width", "height", "rgba", "position"}


def refused_before_c(world, caller, name, value, ctype):
    with pytest.raises(OverflowError) as info:
        create(world, caller, **{name: value})
    assert str(info.value) == range_message(name, value, ctype)
    assert world.bodies() == []


@pytest.mark.parametrize("caller,name,ctype", field_cases(enums=False))
def test_a_def_field_outside_its_c_type_is_refused_and_its_ends_reach_c(monkeypatch, world, caller, name, ctype):
    _, low, high = c_range(ctype)
    for value in (low - 1, high + 1):
        refused_before_c(world, caller, name, value, ctype)
    for value in (low, high):
        assert getattr(def_reaching_c(monkeypatch, world, caller, **{name: value}), name) == value


@pytest.mark.parametrize("caller,name,ctype", field_cases(enums=True))
def test_an_enum_field_outside_int32_is_refused_and_its_members_reach_c(monkeypatch, world, caller, name, ctype):
    _, low, high = c_range(ctype)
    for value in (low - 1, high + 1):
        refused_before_c(world, caller, name, value, ctype)
    for value in (low, high):  # in the C type but no member
        with pytest.raises(ValueError, match=f"^{name}: {value} is not one of ") as info:
            create(world, caller, **{name: value})
        assert not isinstance(info.value, OverflowError)
    for member in (min(_ENUM_FIELDS[name]), max(_ENUM_FIELDS[name])):
        assert getattr(def_reaching_c(monkeypatch, world, caller, **{name: int(member)}), name) == member


def test_def_fields_take_bools_and_numpy_integers_but_not_floats(monkeypatch, world):
    d = def_reaching_c(monkeypatch, world, "World", allow_sleep=True, continuous=False, substeps=np.int64(3))
    assert (d.allow_sleep, d.continuous, d.substeps) == (1, 0, 3)
    d = def_reaching_c(monkeypatch, world, "create_body", is_sensor=True, category_bits=np.uint32(2**32 - 1))
    assert (d.is_sensor, d.category_bits) == (1, 2**32 - 1)
    with pytest.raises(TypeError, match=r"^substeps: expected an integer, got float 2\.0$"):
        World(substeps=2.0)
    with pytest.raises(TypeError, match="^category_bits: expected an integer, got str '1'$"):
        rect(world, 4, 4, category_bits="1")
    assert world.bodies() == []


# ---- the integer arguments of methods ----

@pytest.mark.parametrize("arg", ["x", "y"])
def test_write_pixels_corner_is_checked_as_int32(world, arg):
    body = rect(world, 8, 8)
    for value in (-2**31 - 1, 2**31, 2**32):
        corner = {"x": 0, "y": 0, arg: value}
        with pytest.raises(OverflowError) as info:
            body.write_pixels(corner["x"], corner["y"], np.zeros((2, 2)))
        assert str(info.value) == range_message(arg, value, ctypes.c_int32)
    for value in (-2**31, 2**31 - 1):  # reaches the library, which names the corner it got
        corner = {"x": 0, "y": 0, arg: value}
        e = raises_from_library(physpix.InvalidArgumentError, ["outside"], body.write_pixels, corner["x"], corner["y"],
                                np.zeros((2, 2)))
        assert f"at ({corner['x']}, {corner['y']})" in e.message
    with pytest.raises(TypeError, match=f"^{arg}: expected an integer, got float 1.5$"):
        body.write_pixels(*({"x": 0, "y": 0, arg: 1.5}[k] for k in "xy"), np.zeros((2, 2)))
    body.write_pixels(np.int64(0), np.uint8(0), np.zeros((2, 2)))
    assert body.read_mask().sum() == 64 - 4


def test_paint_weight_is_a_byte(space):
    body = space.create_body(mask=np.zeros((8, 8)) + np.eye(8), position=(0, 0))
    for weight in (-1, 256, 2**32 + 255):
        with pytest.raises(OverflowError) as info:
            body.paint_circle((0, 0), 8, weight=weight)
        assert str(info.value) == range_message("weight", weight, ctypes.c_uint8)
    with pytest.raises(TypeError, match="^weight: expected an integer, got str '255'$"):
        body.paint_circle((0, 0), 8, weight="255")
    assert body.read_mask().sum() == 8
    raises_from_library(physpix.InvalidArgumentError, ["1..255"], body.paint_circle, (0, 0), 8, weight=0)
    assert body.paint_circle((0, 0), 8, weight=255) > 0


def test_a_scheduled_paint_weight_is_a_byte_in_its_32_bit_field(space):
    ground = rect(space, 20, 20, type="static")
    for weight in (-1, 256, 2**32 + 255):
        with pytest.raises(OverflowError, match=rf"^weight: {weight} is outside \[0, 255\]$"):
            space.schedule_paint(1, ground, (0, 0), 4, weight=weight)
    with pytest.raises(TypeError, match="^weight: expected an integer"):
        space.schedule_paint(1, ground, (0, 0), 4, weight=255.0)
    assert space.scheduled_edits() == []
    space.schedule_paint(1, ground, (0, 0), 4, weight=255)
    assert [e.weight for e in space.scheduled_edits()] == [255]


QUERIES = {"raycast": lambda w, bits: w.raycast((-50, 0), (50, 0), mask_bits=bits),
           "query_point": lambda w, bits: w.query_point((0, 0), mask_bits=bits),
           "query_aabb": lambda w, bits: w.query_aabb((-1, -1), (1, 1), mask_bits=bits),
           "query_circle": lambda w, bits: w.query_circle((0, 0), 2, mask_bits=bits)}


@pytest.mark.parametrize("query", QUERIES)
def test_query_mask_bits_are_a_uint32(space, query):
    rect(space, 10, 10, type="static", position=(0, 0), category_bits=0x80000000)
    run = QUERIES[query]
    for bits in (-1, 2**32, 2**32 + 0x80000000):
        with pytest.raises(OverflowError) as info:
            run(space, bits)
        assert str(info.value) == range_message("mask_bits", bits, ctypes.c_uint32)
    with pytest.raises(TypeError, match="^mask_bits: expected an integer"):
        run(space, 1.0)
    assert not run(space, 0) and not run(space, 0x7fffffff)
    assert run(space, 2**32 - 1) and run(space, np.uint32(0x80000000))


@pytest.mark.parametrize("arg", ["width", "height"])
def test_camera_size_is_int32(world, arg):
    before = world.camera
    for value in (-2**31 - 1, 2**31, 2**32 + 64):
        size = {"width": 64, "height": 48, arg: value}
        with pytest.raises(OverflowError) as info:
            world.camera = ((0, 0), 1, size["width"], size["height"])
        assert str(info.value) == range_message(arg, value, ctypes.c_int32)
    for value in (-2**31, 2**31 - 1):  # reaches the library, which prints the size it got
        size = {"width": 64, "height": 48, arg: value}
        e = raises_from_library(physpix.InvalidArgumentError, ["size"], setattr, world, "camera",
                                ((0, 0), 1, size["width"], size["height"]))
        assert f"{size['width']}x{size['height']}" in e.message
    assert world.camera == before


def test_preset_is_an_int32_enum():
    with pytest.raises(OverflowError) as info:
        World.from_preset(2**31)
    assert str(info.value) == range_message("preset", 2**31, ctypes.c_int32)
    with pytest.raises(ValueError, match="^preset: 2147483647 is not one of "):
        World.from_preset(2**31 - 1)
    with pytest.raises(TypeError, match="^preset: expected an integer"):
        World.from_preset(2.0)


def test_a_body_handle_is_a_uint64(world):
    for value in (-1, 2**64):
        with pytest.raises(OverflowError) as info:
            Body(world, value)
        assert str(info.value) == range_message("body_id", value, ctypes.c_uint64)
    body = rect(world, 4, 4)
    assert Body(world, np.uint64(body.id)) == body
    raises_from_library(physpix.InvalidHandleError, ["body"], lambda: Body(world, 2**64 - 1).position)


# ---- paths ----

@pytest.fixture
def files(tmp_path, world):
    """Existing files a path cut at its NUL would name: a PNG, a scene, a snapshot; and where new ones would go."""
    png = tmp_path / "a.png"
    physpix.save_png(png, np.full((3, 5, 4), 200, dtype=np.uint8))
    scene = tmp_path / "scene.json"
    scene.write_text('{"bodies": [{"box": [4, 4]}]}')
    rect(world, 4, 4)
    world.save_snapshot(tmp_path / "snap")
    return {"png": png, "scene": scene, "snap": tmp_path / "snap", "new_png": tmp_path / "new.png",
            "new_snap": tmp_path / "new_snap", "tmp": tmp_path}


PATH_CALLS = {  # name: (argument name, the existing or new file a cut path names, the call)
    "image_info": ("path", "png", lambda world, p: physpix.image_info(p)),
    "load_png": ("path", "png", lambda world, p: physpix.load_png(p)),
    "save_png": ("path", "new_png", lambda world, p: physpix.save_png(p, np.zeros((2, 2, 4), dtype=np.uint8))),
    "load_scene": ("path", "scene", lambda world, p: World.load_scene(p)),
    "load_snapshot": ("folder", "snap", lambda world, p: World.load_snapshot(p)),
    "save_snapshot": ("folder", "new_snap", lambda world, p: world.save_snapshot(p)),
}
PATH_FORMS = {"str": str, "bytes": os.fsencode, "Path": Path}


@pytest.mark.parametrize("form", PATH_FORMS)
@pytest.mark.parametrize("call", PATH_CALLS)
def test_a_nul_in_a_path_is_refused_not_cut(world, files, call, form):
    arg, target, run = PATH_CALLS[call]
    path = PATH_FORMS[form](f"{files[target]}\0.txt")
    with pytest.raises(ValueError) as info:
        run(world, path)
    assert str(info.value) == f"{arg}: {path!r} contains a NUL character"
    assert sorted(p.name for p in files["tmp"].iterdir()) == ["a.png", "scene.json", "snap"], "a refused call wrote"


@pytest.mark.parametrize("call", PATH_CALLS)
def test_a_path_of_the_wrong_kind_is_a_type_error_naming_it(world, call):
    arg, _, run = PATH_CALLS[call]
    with pytest.raises(TypeError, match=f"^{arg}: expected a str, bytes or os.PathLike path, got int 5$"):
        run(world, 5)
