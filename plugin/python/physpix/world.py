"""World and Body: the C ABI's calls as methods and properties, numpy arrays in and out.

Units everywhere: pixels, seconds, radians; world y points down. Every failing call raises
the PhysPixError subclass of its status with the library's message.
"""
from __future__ import annotations

import ctypes
import operator
import os
import weakref
from ctypes import POINTER, byref, c_double, c_float, c_int32, c_int64, c_uint8, c_uint32, c_uint64
from dataclasses import astuple, dataclass, fields as dataclass_fields
from enum import IntEnum
from typing import (Any, Callable, Collection, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Type, TypeVar,
                    Union)

import numpy as np

from . import _native as N
from .enums import (DEBUG_DRAW_ALL, Backend, BodyType, ContactMode, EditType, EventType, JointType, NormalMethod,
                    Preset)
from .errors import IntegerRangeError, InvalidArgumentError, LimitError, PhysPixError

try:  # the array hints' names, so that typing.get_type_hints resolves them (numpy.typing.NDArray: numpy >= 1.21)
    import numpy.typing as npt
except ImportError:  # an older numpy runs the package all the same; only its hints do not resolve at run time
    pass

#: A vector as the package returns it: (x, y).
Vec2 = Tuple[float, float]
#: A vector as the package takes it: any (x, y) pair of numbers, a tuple, a list or a numpy array of two.
Vec2Like = Union[Sequence[float], np.ndarray]
#: A file or folder path, as os.fsencode takes it.
PathLike = Union[str, bytes, os.PathLike]

_E = TypeVar("_E", bound=IntEnum)
_S = TypeVar("_S", bound=ctypes.Structure)
_W = TypeVar("_W", bound="World")

lib = N.lib

# Def fields that take an enum: the enum class accepts members, ints and lower-case names.
_ENUM_FIELDS: Dict[str, Type[IntEnum]] = {"backend": Backend, "normal_method": NormalMethod,
                                          "contact_mode": ContactMode, "type": BodyType}
# Body def fields that create_body fills from the numpy arrays, never from keywords.
_PLANE_FIELDS = ("rgba", "mask", "weights")


def _check_range(value: int, low: int, high: int, what: str, kind: str = "") -> int:
    """value as an int within low..high: ctypes would wrap an int outside the C type's range silently (2**32 + 5
    into a uint32 is 5), so that is an IntegerRangeError; a float or a str is a TypeError, never truncated."""
    try:
        number = operator.index(value)  # ints, bools and numpy integers
    except TypeError:
        raise TypeError(f"{what}: expected an integer, got {type(value).__name__} {value!r}") from None
    if not low <= number <= high:
        raise IntegerRangeError(f"{what}: {number} is outside {kind}[{low}, {high}]")
    return number


def _is_c_int(ctype: Any) -> bool:
    """Whether a ctypes type is a C integer (int8 … uint64, whatever alias names it)."""
    return isinstance(ctype, type) and issubclass(ctype, ctypes._SimpleCData) and ctype._type_ in "bBhHiIlLqQ"


def _c_int(value: int, ctype: Type[ctypes._SimpleCData], what: str) -> int:
    """value as an int that the C integer type ctype holds, checked as _check_range does."""
    bits = 8 * ctypes.sizeof(ctype)
    if ctype(-1).value < 0:
        return _check_range(value, -2 ** (bits - 1), 2 ** (bits - 1) - 1, what, f"int{bits} ")
    return _check_range(value, 0, 2 ** bits - 1, what, f"uint{bits} ")


def _path(path: PathLike, what: str) -> bytes:
    """A path as the bytes a C call takes; a NUL would end the C string early and name another file."""
    try:
        encoded = os.fsencode(path)
    except TypeError:
        raise TypeError(f"{what}: expected a str, bytes or os.PathLike path, got {type(path).__name__} "
                        f"{path!r}") from None
    if b"\0" in encoded:
        raise ValueError(f"{what}: {path!r} contains a NUL character")
    return encoded


def enum_value(cls: Type[_E], value: Union[_E, int, str], what: str) -> _E:
    """An enum member from a member, an int or a case-insensitive name such as "area_gradient"."""
    if isinstance(value, str):
        try:
            return cls[value.upper()]
        except KeyError:
            choices = ", ".join(repr(m.name.lower()) for m in cls)
            raise ValueError(f"{what}: {value!r} is not one of {choices}") from None
    number = _c_int(value, N.c_enum, what)  # the enum's C type first: an int outside it is an IntegerRangeError
    try:
        return cls(number)
    except ValueError:
        choices = ", ".join(f"{m.name.lower()!r} ({int(m)})" for m in cls)
        raise ValueError(f"{what}: {value!r} is not one of {choices}") from None


def vec2(value: Vec2Like, what: str = "vector") -> N.pp_vec2:
    """A pp_vec2 from any (x, y) pair of numbers."""
    try:
        x, y = value
        return N.pp_vec2(float(x), float(y))
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected an (x, y) pair of numbers, got {value!r}") from None


def _fill_def(struct: ctypes.Structure, values: Mapping[str, Any], caller: str, skip: Collection[str] = ()) -> None:
    """Set def fields from keywords named as in the C struct; unknown names are a TypeError."""
    types = {field[0]: field[1] for field in struct._fields_}
    for name, value in values.items():
        if name in skip:
            raise TypeError(f"{caller}(): {name!r} comes from the arrays, not from a keyword")
        if name not in types:
            raise TypeError(f"{caller}() got an unexpected keyword argument {name!r}")
        if name in _ENUM_FIELDS:
            value = enum_value(_ENUM_FIELDS[name], value, name)
        elif types[name] is N.pp_vec2:
            value = vec2(value, name)
        elif _is_c_int(types[name]):
            value = _c_int(value, types[name], name)
        try:
            setattr(struct, name, value)
        except TypeError as exc:  # ctypes' own message does not say which field
            raise TypeError(f"{name}: {exc}") from None


def _dtype_of(struct: Type[ctypes.Structure], shapes: Mapping[str, Tuple[str, Tuple[int, ...]]]) -> np.dtype:
    """A numpy dtype with a ctypes struct's field offsets and size; shapes: field name to (numpy type, shape)."""
    names = [f for f, _ in struct._fields_]
    return np.dtype({"names": names, "formats": [(shapes[f][0], shapes[f][1]) if shapes[f][1] else shapes[f][0]
                                                  for f in names],
                     "offsets": [getattr(struct, f).offset for f in names], "itemsize": ctypes.sizeof(struct)})


BODY_STATE_DTYPE = _dtype_of(N.pp_body_state, {
    "body": ("<u8", ()), "position": ("<f4", (2,)), "angle": ("<f4", ()), "linear_velocity": ("<f4", (2,)),
    "angular_velocity": ("<f4", ()), "awake": ("<u4", ()), "user_data": ("<u8", ())})

#: What World.debug_draw returns: pp_debug_segment's fields (kind is a DebugKind value, rgba 0xRRGGBBAA).
DEBUG_SEGMENT_DTYPE = _dtype_of(N.pp_debug_segment, {
    "a": ("<f4", (2,)), "b": ("<f4", (2,)), "rgba": ("<u4", ()), "kind": ("<i4", ()), "body": ("<u8", ())})


def _read_list(fn: Callable[..., Any], item_type: Type[_S], *args: Any, guess: int = 0) -> List[_S]:
    """All items of a snapshot getter (bodies, contacts, collide): read with a first guess of the count
    (0: just ask it), then again with the total the library reported if that was more."""
    capacity, count = guess, c_int32(0)
    while True:
        buf = (item_type * capacity)() if capacity else None
        fn(*args, buf, capacity, byref(count))
        if count.value <= capacity:
            return list(buf[:count.value]) if buf is not None else []
        capacity = count.value


def _check_plane_size(a: np.ndarray, name: str) -> None:
    """A plane whose height or width the C int32 fields cannot hold is an IntegerRangeError (a ValueError) naming
    it, raised before anything copies it: ctypes would wrap a width of 2**32 + 16 to 16, and a broadcast array
    that size would be 4 GiB once made contiguous."""
    for axis, size in zip(("height", "width"), a.shape[:2]):
        _c_int(size, c_int32, f"{name} {axis}")


def _as_u8(array: npt.ArrayLike, name: str, ndim: int, channels: Optional[int] = None) -> npt.NDArray[np.uint8]:
    """A C-contiguous uint8 copy-free view where possible; integer arrays must hold 0..255."""
    a = np.asarray(array)
    if a.ndim != ndim or (channels is not None and a.shape[-1] != channels):
        want = "(height, width, 4)" if channels else "(height, width)"
        raise ValueError(f"{name}: expected an array of shape {want}, got shape {a.shape}")
    _check_plane_size(a, name)
    if a.dtype != np.uint8:
        if a.dtype.kind not in "iu" or (a.size and (a.min() < 0 or a.max() > 255)):
            raise ValueError(f"{name}: expected uint8 values 0..255, got dtype {a.dtype}")
        a = a.astype(np.uint8)
    return np.ascontiguousarray(a)


def _mask_u8(mask: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """A collision mask as C-contiguous uint8: any dtype, non-zero is solid."""
    m = np.asarray(mask)
    if m.ndim != 2:
        raise ValueError(f"mask: expected an array of shape (height, width), got shape {m.shape}")
    _check_plane_size(m, "mask")
    return np.ascontiguousarray(m != 0, dtype=np.uint8)


def _mask_bits(bits: int) -> int:
    """Collision filter bits as the uint32 the library takes."""
    return _c_int(bits, c_uint32, "mask_bits")


def _u8_ptr(array: Optional[np.ndarray]) -> Any:
    return None if array is None else array.ctypes.data_as(N.u8p)


def _planes(mask: Optional[npt.ArrayLike], rgba: Optional[npt.ArrayLike], weights: Optional[npt.ArrayLike]
            ) -> Tuple[Dict[str, npt.NDArray[np.uint8]], Tuple[int, int]]:
    """Validated planes and their common (height, width); a disagreement between them is a ValueError."""
    planes: Dict[str, npt.NDArray[np.uint8]] = {}
    if mask is not None:
        planes["mask"] = _mask_u8(mask)
    if rgba is not None:
        planes["rgba"] = _as_u8(rgba, "rgba", 3, channels=4)
    if weights is not None:
        planes["weights"] = _as_u8(weights, "weights", 2)
    shapes = {name: a.shape[:2] for name, a in planes.items()}
    if len(set(shapes.values())) > 1:
        raise ValueError("planes disagree in (height, width): " + ", ".join(f"{k} {v}" for k, v in shapes.items()))
    if not planes:
        raise ValueError("create_body needs a mask or an rgba array")
    if "weights" in planes and len(planes) == 1:
        raise ValueError("weights alone are not a shape: give a mask or an rgba array too")
    return planes, next(iter(shapes.values()))


@dataclass(frozen=True)
class Contact:
    """One contact point: normal points from a to b; point in world px, depth in px; normal_impulse, mass·px/s,
    is what the solver applied along the normal in the last substep (0 from collide)."""
    a: Body
    b: Body
    point: Vec2
    normal: Vec2
    depth: float
    pixel_count: int
    normal_impulse: float


@dataclass(frozen=True)
class Event:
    """Something that happened to a body (SPLIT: other is the new body; DESTROYED: other is None; CONTACT_*:
    other is the body touched; SENSOR_*: body is the sensor, other the body overlapping it). CONTACT_BEGIN and
    SENSOR_BEGIN also give the first contact's world point (px), the unit normal from body to other, and the
    speed at which they closed along it (px/s); other events give zeros. JOINT_BROKEN: body is the joint's body_a
    (None for the world), other its body_b."""
    type: EventType
    body: Body
    other: Optional[Body]
    point: Vec2
    normal: Vec2
    approach_speed: float
    joint: Optional[Joint] = None  # JOINT_BROKEN: the joint, now stale (body and other are its bodies)


@dataclass(frozen=True)
class RaycastHit:
    """The nearest solid pixel a ray meets: the body, the world point where the ray enters it (px), the unit
    surface normal there (out of the body), and where along from → to it lies (0..1)."""
    body: Body
    point: Vec2
    normal: Vec2
    fraction: float


@dataclass(frozen=True)
class CharacterMove:
    """Where World.move_character took a character: its end position (px), the velocity asked for less what the
    surfaces took away (px/s), whether it stands on ground no steeper than max_slope, that ground's unit normal
    ((0, 0) in the air), body (None in the air) and velocity under the character (px/s), and the surfaces met."""
    position: Vec2
    velocity: Vec2
    grounded: bool
    ground_normal: Vec2
    ground_body: Optional[Body]
    ground_velocity: Vec2
    surfaces: int


@dataclass(frozen=True)
class StepStats:
    """What the last step did: times in milliseconds, counts, and the backend that ran."""
    broadphase_ms: float
    narrowphase_ms: float
    solver_ms: float
    total_ms: float
    bodies: int
    awake_bodies: int
    pairs: int
    contacts: int
    pixels_tested: int
    backend: Backend
    swept_stops: int
    threads: int


@dataclass(frozen=True)
class Camera:
    """A renderer's view: world point at the image centre (px), image px per world px, image size (px)."""
    center: Vec2
    zoom: float
    width: int
    height: int


@dataclass(frozen=True)
class ScheduledEdit:
    """A pending timed edit: world time (s), circle centre (px) and radius (px); body None erases every body."""
    time: float
    type: EditType
    body: Optional[Body]
    center: Vec2
    radius: float
    weight: int


@dataclass(frozen=True)
class CollisionView:
    """A pair's sampled grid: size (cells), world centre of cell (0, 0) and the steps along x and y (px),
    the global normal from a to b (zero when apart), and the intersection and critical cell counts."""
    width: int
    height: int
    origin: Vec2
    step_x: Vec2
    step_y: Vec2
    normal: Vec2
    intersection: int
    critical: int


def _destroy_world(world_id: int) -> None:
    """Finalizer of a World never closed: destroy it, quietly (at exit nobody can handle an error)."""
    try:
        lib.pp_world_destroy(N.pp_world(world_id))
    except PhysPixError:
        pass


class World:
    """A physics world; keywords are pp_world_def field names (gravity=(0, 980) px/s², backend="cpu", …)."""

    _handle: N.pp_world
    _finalizer: weakref.finalize

    def __init__(self, **fields: Any) -> None:
        self._create(lib.pp_world_def_default(), fields, "World")

    @classmethod
    def from_preset(cls: Type[_W], preset: Union[Preset, int, str], **fields: Any) -> _W:
        """A world from a preset ("fast", "balanced" = the default, "accurate"); keywords override its fields."""
        world = cls.__new__(cls)
        world._create(lib.pp_world_def_preset(enum_value(Preset, preset, "preset")), fields, "from_preset")
        return world

    def _create(self, d: N.pp_world_def, fields: Mapping[str, Any], caller: str) -> None:
        _fill_def(d, fields, caller)
        handle = N.pp_world()
        lib.pp_world_create(byref(d), byref(handle))
        self._adopt(handle)

    def _adopt(self, handle: N.pp_world) -> None:
        self._handle = handle
        self._finalizer = weakref.finalize(self, _destroy_world, handle.id)

    @classmethod
    def _created_by(cls: Type[_W], fn: Callable[..., Any], path: PathLike, what: str) -> _W:
        encoded = _path(path, what)
        world = cls.__new__(cls)
        handle = N.pp_world()
        fn(encoded, byref(handle))
        world._adopt(handle)
        return world

    @classmethod
    def load_scene(cls: Type[_W], path: PathLike) -> _W:
        """A world from a JSON scene file (settings, camera, bodies, timed edits); PNG paths are read only from
        inside its folder."""
        return cls._created_by(lib.pp_world_load_scene, path, "path")

    @classmethod
    def load_snapshot(cls: Type[_W], folder: PathLike) -> _W:
        """A world from a snapshot folder; stepping it continues exactly as the saved world would have."""
        return cls._created_by(lib.pp_world_load_snapshot, folder, "folder")

    def save_snapshot(self, folder: PathLike) -> None:
        """Write the world's whole state into a new folder (world.json and PNG planes)."""
        lib.pp_world_save_snapshot(self._handle, _path(folder, "folder"))

    def save_state(self) -> bytes:
        """The world's whole state as bytes in memory, for rollback and undo (restore_state, load_state)."""
        size = c_int64()
        try:
            lib.pp_world_save_state(self._handle, None, 0, byref(size))
        except LimitError:  # the bytes it needs are in size
            pass
        buf = ctypes.create_string_buffer(size.value)
        lib.pp_world_save_state(self._handle, buf, size.value, byref(size))
        return buf.raw[:size.value]

    def restore_state(self, data: bytes) -> None:
        """Put the world back as it was when it saved these bytes: bodies and joints made since go stale, those
        destroyed since live again. Changed or cut bytes raise FormatError, another world's InvalidArgumentError;
        either way the world is unchanged."""
        data = bytes(data)
        lib.pp_world_restore_state(self._handle, data, len(data))

    @classmethod
    def load_state(cls: Type[_W], data: bytes) -> _W:
        """A new world from saved state bytes; it continues exactly as the saved world would have."""
        data = bytes(data)
        world = cls.__new__(cls)
        handle = N.pp_world()
        lib.pp_world_load_state(data, len(data), byref(handle))
        world._adopt(handle)
        return world

    @property
    def hash(self) -> int:
        """64 bits over everything the next steps depend on (0..2**64-1): equal hashes, equal futures, on either
        backend and in any run."""
        h = c_uint64()
        lib.pp_world_get_hash(self._handle, byref(h))
        return h.value

    def close(self) -> None:
        """Destroy the world and its bodies; later calls with it raise InvalidHandleError. Idempotent."""
        if self._finalizer.detach() is not None:
            lib.pp_world_destroy(self._handle)

    def __enter__(self: _W) -> _W:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if not self._finalizer.alive else "open"
        return f"<physpix.World id={self._handle.id:#x} {state}>"

    @property
    def id(self) -> int:
        """The opaque pp_world handle value."""
        return self._handle.id

    def _body(self, handle: N.pp_body) -> Optional[Body]:
        return Body(self, handle.id) if handle.id else None

    def step(self, dt: float) -> None:
        """Advance the world by dt seconds (0 < dt ≤ 1)."""
        lib.pp_world_step(self._handle, dt)

    def create_body(self, mask: Optional[npt.ArrayLike] = None, rgba: Optional[npt.ArrayLike] = None,
                    weights: Optional[npt.ArrayLike] = None, **fields: Any) -> Body:
        """A body from numpy planes (mask (h, w) non-zero solid; rgba (h, w, 4) uint8; weights (h, w) 0..255)
        and pp_body_def fields as keywords (type="static", position=(x, y) px, angle rad, density, …)."""
        planes, (height, width) = _planes(mask, rgba, weights)
        d = lib.pp_body_def_default()
        _fill_def(d, fields, "create_body", skip=_PLANE_FIELDS + ("width", "height"))
        d.width, d.height = width, height
        for name, array in planes.items():
            setattr(d, name, _u8_ptr(array))
        handle = N.pp_body()
        # `planes` keeps the arrays alive through the call; the library copies them.
        lib.pp_body_create(self._handle, byref(d), byref(handle))
        return Body(self, handle.id)

    def bodies(self) -> List[Body]:
        """Every live body."""
        return [Body(self, h.id) for h in _read_list(lib.pp_world_get_bodies, N.pp_body, self._handle)]

    def body(self, body_id: int) -> Body:
        """The Body of a handle id (body_states()'s "body", Body.id); InvalidHandleError if no live body of this
        world has it."""
        body = Body(self, body_id)
        body._call(lib.pp_body_is_awake, byref(c_int32()))  # the library knows stale and foreign ids
        return body

    def body_states(self) -> npt.NDArray[Any]:
        """Every live body's state in one call, in bodies() order: a numpy structured array with fields body (id),
        position (pivot, 2 floats, px), angle (rad), linear_velocity (2, px/s), angular_velocity (rad/s), awake,
        user_data."""
        count = c_int32(0)
        lib.pp_world_get_body_states(self._handle, None, 0, byref(count))
        while True:
            out = np.zeros(count.value, dtype=BODY_STATE_DTYPE)
            ptr = out.ctypes.data_as(POINTER(N.pp_body_state))
            lib.pp_world_get_body_states(self._handle, ptr, len(out), byref(count))
            if count.value <= len(out):
                return out[:count.value]

    def create_joint(self, type: Union[JointType, int, str], body_a: Optional[Body] = None,
                     body_b: Optional[Body] = None, **fields: Any) -> Joint:
        """A joint of a type ("revolute", "prismatic", "distance", "weld", "mouse", "wheel", "motor") between two
        bodies (None: the static world) with pp_joint_def fields as keywords: anchor_a=(x, y) world px, axis,
        enable_limit, lower, upper, enable_motor, motor_speed, max_motor_force, min_length, max_length,
        spring_hertz, spring_damping_ratio, max_force, break_force, collide_connected, user_data, target,
        angular_hertz, angular_damping_ratio, break_torque, linear_offset, angular_offset, max_torque,
        correction_factor."""
        jt = enum_value(JointType, type, "type")
        d = lib.pp_joint_def_default(jt)
        _fill_def(d, fields, "create_joint", skip=("struct_size", "type", "body_a", "body_b"))
        for name, body in (("body_a", body_a), ("body_b", body_b)):
            if body is not None and not isinstance(body, Body):
                raise TypeError(f"create_joint(): {name} must be a Body or None, got {body!r}")
            setattr(d, name, body._handle if body is not None else N.pp_body(0))
        handle = N.pp_joint()
        lib.pp_joint_create(self._handle, byref(d), byref(handle))
        return Joint(self, handle.id)

    def joints(self) -> List[Joint]:
        """Every live joint."""
        return [Joint(self, h.id) for h in _read_list(lib.pp_world_get_joints, N.pp_joint, self._handle)]

    @property
    def gravity(self) -> Vec2:
        """The world's gravity, (x, y) px/s²; settable (wakes every sleeping body)."""
        g = self.settings["gravity"]
        return g[0], g[1]

    @gravity.setter
    def gravity(self, value: Vec2Like) -> None:
        lib.pp_world_set_gravity(self._handle, vec2(value, "gravity"))

    def _contacts(self, raw: Iterable[N.pp_contact]) -> List[Contact]:
        return [Contact(Body(self, c.a.id), Body(self, c.b.id), (c.point.x, c.point.y), (c.normal.x, c.normal.y),
                        c.depth, c.pixel_count, c.normal_impulse) for c in raw]

    def contacts(self) -> List[Contact]:
        """The contacts of the last substep."""
        return self._contacts(_read_list(lib.pp_world_get_contacts, N.pp_contact, self._handle))

    def debug_draw(self, flags: int = DEBUG_DRAW_ALL, lower: Optional[Vec2Like] = None,
                   upper: Optional[Vec2Like] = None) -> np.ndarray:
        """The world's physics as line segments (pp_world_debug_draw), a numpy structured array with fields a and b
        (world px, 2 floats each), rgba (uint32, 0xRRGGBBAA), kind (a DebugKind value) and body (the body's id, 0 for
        the static world). flags: DEBUG_DRAW_* bits; lower, upper: the view box, world px (None: unbounded)."""
        big = 3.4028234663852886e38  # FLT_MAX: the box a float can hold
        lo = vec2(lower, "lower") if lower is not None else N.pp_vec2(-big, -big)
        hi = vec2(upper, "upper") if upper is not None else N.pp_vec2(big, big)
        count = c_int32(0)
        fl = _c_int(flags, c_uint32, "flags")
        lib.pp_world_debug_draw(self._handle, fl, lo, hi, None, 0, byref(count))
        while True:
            out = np.zeros(count.value, dtype=DEBUG_SEGMENT_DTYPE)
            ptr = out.ctypes.data_as(POINTER(N.pp_debug_segment))
            lib.pp_world_debug_draw(self._handle, fl, lo, hi, ptr, len(out), byref(count))
            if count.value <= len(out):
                return out[:count.value]

    def collide(self, a: Body, b: Body) -> List[Contact]:
        """Run the narrowphase on one pair at the current poses, without stepping; normals point from a to b."""
        # A pair makes at most two contacts (MANIFOLD): one call, not a count then a read of the narrowphase.
        return self._contacts(_read_list(lib.pp_world_collide, N.pp_contact, self._handle, a._handle, b._handle,
                                         guess=4))

    def events(self) -> List[Event]:
        """The events since they were last read, oldest first; reading forgets them."""
        out: List[Event] = []
        count = c_int32(0)
        lib.pp_world_get_events(self._handle, None, 0, byref(count))
        # Reading consumes what it writes, so read until nothing is pending rather than re-asking a total.
        while count.value > 0:
            buf = (N.pp_event * count.value)()
            lib.pp_world_get_events(self._handle, buf, count.value, byref(count))
            written = min(count.value, len(buf))
            out += [Event(EventType(e.type), Body(self, e.body.id), self._body(e.other), (e.point.x, e.point.y),
                          (e.normal.x, e.normal.y), e.approach_speed, Joint(self, e.joint.id) if e.joint.id else None)
                    for e in buf[:written]]
            count.value -= written
        return out

    def raycast(self, from_: Vec2Like, to: Vec2Like, mask_bits: int = 0xffffffff) -> Optional[RaycastHit]:
        """The nearest solid pixel on the segment from → to (world px) of a body whose category_bits meet
        mask_bits (sensors skipped), as a RaycastHit, or None; a ray starting inside a solid pixel hits at 0."""
        hit, out = c_int32(0), N.pp_raycast_hit()
        lib.pp_world_raycast(self._handle, vec2(from_, "from_"), vec2(to, "to"), _mask_bits(mask_bits), byref(out),
                             byref(hit))
        return self._hit(out) if hit.value else None

    def _hit(self, out: Any) -> RaycastHit:
        return RaycastHit(Body(self, out.body.id), (out.point.x, out.point.y), (out.normal.x, out.normal.y),
                          out.fraction)

    def raycast_all(self, start: Vec2Like, end: Vec2Like, mask_bits: int = 0xffffffff) -> List[RaycastHit]:
        """Every body the segment start → end (world px) enters, as raycast would hit it (its first entry into
        each), nearest first; category_bits must meet mask_bits, sensors are skipped."""
        return [self._hit(h) for h in _read_list(lib.pp_world_raycast_all, N.pp_raycast_hit, self._handle,
                                                 vec2(start, "start"), vec2(end, "end"), _mask_bits(mask_bits))]

    def cast_body(self, body: Body, translation: Vec2Like, mask_bits: int = 0xffffffff) -> Optional[RaycastHit]:
        """Sweep the body's solid pixels (their squares) along translation (px, rotation held) against the bodies
        whose category_bits meet mask_bits (itself, sensors, and bodies its filter or joints keep apart skipped):
        the first touch as a RaycastHit (fraction: the part of translation it moves free, to 1/16 px; the normal
        out of the body hit; 0 when it overlaps one at the start), or None. Nothing in the world changes."""
        hit, out = c_int32(0), N.pp_raycast_hit()
        lib.pp_world_cast_body(self._handle, body._handle, vec2(translation, "translation"),
                               _mask_bits(mask_bits), byref(out), byref(hit))
        return self._hit(out) if hit.value else None

    def explode(self, position: Vec2Like, radius: float, falloff: float = 0.0,
                impulse_per_length: Optional[float] = None, erase_radius: float = 0.0, mask_bits: int = 0xffffffff,
                erase_mask_bits: int = 0xffffffff) -> int:
        """Erase within erase_radius px of position (world px) from the bodies whose category_bits meet
        erase_mask_bits, then push each dynamic body (category_bits meeting mask_bits) with a solid pixel within
        radius + falloff px: impulse_per_length (mass·px/s per px; None: PP_EXPLOSION_IMPULSE_PER_LENGTH) × its
        solid extent across the blast, at its pixel nearest position, full within radius and falling linearly to 0
        at radius + falloff. Returns the pixels erased."""
        d = lib.pp_explosion_def_default()
        d.position = vec2(position, "position")
        d.radius, d.falloff, d.erase_radius = radius, falloff, erase_radius
        if impulse_per_length is not None:
            d.impulse_per_length = impulse_per_length
        d.mask_bits, d.erase_mask_bits = _mask_bits(mask_bits), _mask_bits(erase_mask_bits)
        changed = c_int32(0)
        lib.pp_world_explode(self._handle, byref(d), byref(changed))
        return changed.value

    def move_character(self, position: Vec2Like, velocity: Vec2Like, dt: float, **fields: Any) -> CharacterMove:
        """Move a character's capsule (not a body: the caller keeps its position and velocity) from position (px)
        along velocity (px/s) × dt (s) against the solid pixels, sliding along them, climbing steps and keeping to
        the ground. Keywords are pp_character_def's fields: radius, half_height, step_height, snap_distance (px),
        max_slope (rad), mask_bits; those left out keep pp_character_def_default's. Nothing in the world changes."""
        d = lib.pp_character_def_default()
        _fill_def(d, fields, "move_character", skip=("struct_size",))
        out = N.pp_character_move()
        lib.pp_world_move_character(self._handle, byref(d), vec2(position, "position"), vec2(velocity, "velocity"),
                                    dt, byref(out))
        return CharacterMove((out.position.x, out.position.y), (out.velocity.x, out.velocity.y), bool(out.grounded),
                             (out.ground_normal.x, out.ground_normal.y),
                             Body(self, out.ground_body.id) if out.ground_body.id else None,
                             (out.ground_velocity.x, out.ground_velocity.y), out.surfaces)

    def _query(self, fn: Callable[..., Any], *args: Any) -> List[Body]:
        return [Body(self, h.id) for h in _read_list(fn, N.pp_body, self._handle, *args)]

    def query_point(self, point: Vec2Like, mask_bits: int = 0xffffffff) -> List[Body]:
        """Bodies (category_bits meeting mask_bits, sensors skipped) with a solid pixel whose square contains
        the world point (px), in slot order."""
        return self._query(lib.pp_world_query_point, vec2(point, "point"), _mask_bits(mask_bits))

    def query_aabb(self, lower: Vec2Like, upper: Vec2Like, mask_bits: int = 0xffffffff) -> List[Body]:
        """Bodies with a solid pixel whose centre lies in the world box [lower, upper] (px), as query_point."""
        return self._query(lib.pp_world_query_aabb, vec2(lower, "lower"), vec2(upper, "upper"),
                           _mask_bits(mask_bits))

    def query_circle(self, center: Vec2Like, radius: float, mask_bits: int = 0xffffffff) -> List[Body]:
        """Bodies with a solid pixel whose centre lies within radius px of a world point (px), as query_point:
        the bodies erase_circle would change."""
        return self._query(lib.pp_world_query_circle, vec2(center, "center"), radius, _mask_bits(mask_bits))

    def stats(self) -> StepStats:
        """Statistics of the last step."""
        s = N.pp_step_stats()
        lib.pp_world_get_stats(self._handle, byref(s))
        values = {f.name: getattr(s, f.name) for f in dataclass_fields(StepStats)}
        values["backend"] = Backend(values["backend"])
        return StepStats(**values)

    def erase_circle(self, center: Vec2Like, radius: float) -> int:
        """Erase every body's pixels within radius px of a world point (px); returns the pixels erased."""
        changed = c_int32(0)
        lib.pp_world_erase_circle(self._handle, vec2(center, "center"), radius, byref(changed))
        return changed.value

    @property
    def time(self) -> float:
        """Simulated time since the world was created, s (the sum of every step's dt)."""
        t = c_double()
        lib.pp_world_get_time(self._handle, byref(t))
        return t.value

    @property
    def contact_events(self) -> bool:
        """Whether CONTACT_BEGIN/END events are queued (the world def's contact_events); settable."""
        return bool(self.settings["contact_events"])

    @contact_events.setter
    def contact_events(self, enabled: bool) -> None:
        lib.pp_world_set_contact_events(self._handle, 1 if enabled else 0)

    @property
    def settings(self) -> Dict[str, Any]:
        """The pp_world_def the world runs with, as a dict of field name to value (vectors as (x, y))."""
        d = N.pp_world_def()
        lib.pp_world_get_def(self._handle, byref(d))
        out: Dict[str, Any] = {}
        for name, *_ in d._fields_[1:]:
            v = getattr(d, name)
            out[name] = (v.x, v.y) if isinstance(v, N.pp_vec2) else _ENUM_FIELDS[name](v) if name in _ENUM_FIELDS else v
        return out

    @property
    def camera(self) -> Camera:
        """The world's Camera (a scene's, or the default); set a Camera or (center px, zoom, width px, height px)."""
        c = N.pp_camera()
        lib.pp_world_get_camera(self._handle, byref(c))
        return Camera((c.center.x, c.center.y), c.zoom, c.width, c.height)

    @camera.setter
    def camera(self, value: Union[Camera, Tuple[Vec2Like, float, int, int]]) -> None:
        center, zoom, width, height = astuple(value) if isinstance(value, Camera) else value
        c = N.pp_camera(vec2(center, "center"), zoom, _c_int(width, c_int32, "width"),
                        _c_int(height, c_int32, "height"))
        lib.pp_world_set_camera(self._handle, byref(c))

    def _schedule(self, time: float, edit_type: EditType, body: Optional[Body], center: Vec2Like, radius: float,
                  weight: int) -> None:
        e = N.pp_timed_edit(time=time, type=edit_type, weight=weight, center=vec2(center, "center"), radius=radius)
        e.body = body._handle if body is not None else N.pp_body()
        lib.pp_world_schedule_edit(self._handle, byref(e))

    def schedule_erase(self, time: float, center: Vec2Like, radius: float, body: Optional[Body] = None) -> None:
        """Erase at world time (s) the pixels within radius px of a world point (px): of body, or of every body."""
        self._schedule(time, EditType.ERASE_CIRCLE, body, center, radius, 0)

    def schedule_paint(self, time: float, body: Body, center: Vec2Like, radius: float, weight: int = 255) -> None:
        """Make solid at world time (s), with weight 1..255, body's pixels within radius px of a world point (px)."""
        # A byte as in paint_circle, though the field is 32-bit; the library refuses 0 itself.
        self._schedule(time, EditType.PAINT_CIRCLE, body, center, radius, _check_range(weight, 0, 255, "weight"))

    def scheduled_edits(self) -> List[ScheduledEdit]:
        """The edits still pending, in the order they will apply."""
        return [ScheduledEdit(e.time, EditType(e.type), self._body(e.body), (e.center.x, e.center.y), e.radius,
                              e.weight)
                for e in _read_list(lib.pp_world_get_scheduled_edits, N.pp_timed_edit, self._handle)]

    def debug_collision(self, a: Body, b: Body
                        ) -> Tuple[npt.NDArray[np.uint8], npt.NDArray[np.float32], CollisionView]:
        """A pair's sampled grid at the current poses: (cells (h, w) uint8 of CELL_* flags, local normals
        (h, w, 2) float32 in world axes on critical cells, zero elsewhere, CollisionView)."""
        v = N.pp_collision_view()
        args = (self._handle, a._handle, b._handle)
        try:  # capacity 0 asks for the grid's size; a non-empty grid refuses it but fills the view
            lib.pp_world_debug_collision(*args, None, None, 0, byref(v))
        except InvalidArgumentError:
            if v.width * v.height == 0:
                raise
        cells = np.zeros((v.height, v.width), dtype=np.uint8)
        normals = np.zeros((v.height, v.width, 2), dtype=np.float32)
        if cells.size:
            lib.pp_world_debug_collision(*args, _u8_ptr(cells), normals.ctypes.data_as(POINTER(N.pp_vec2)),
                                         cells.size, byref(v))
        view = CollisionView(v.width, v.height, (v.origin.x, v.origin.y), (v.step_x.x, v.step_x.y),
                             (v.step_y.x, v.step_y.y), (v.normal.x, v.normal.y), v.intersection, v.critical)
        return cells, normals, view


class _InWorld:
    """A value handle of something in a World (a body, a joint); equal when world and ids are."""

    __slots__ = ("_world", "_handle")
    _world: World
    _handle: Any
    _ctype: Type[ctypes.Structure]  # the C handle struct, set by each kind

    def __init__(self, world: World, handle_id: int) -> None:
        self._world = world
        self._handle = self._ctype(_c_int(handle_id, c_uint64, f"{type(self).__name__.lower()}_id"))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, type(self)) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def _key(self) -> Tuple[int, int]:
        return self._world._handle.id, self._handle.id

    def __repr__(self) -> str:
        return f"<physpix.{type(self).__name__} id={self._handle.id:#x}>"

    def _call(self, fn: Callable[..., Any], *args: Any) -> Any:
        return fn(self._world._handle, self._handle, *args)

    @property
    def world(self) -> World:
        """The World it lives in."""
        return self._world

    @property
    def id(self) -> int:
        """The opaque handle value (pp_body's, pp_joint's)."""
        return self._handle.id


class Body(_InWorld):
    """A body of a World: a value handle; equal when world and body ids are."""

    __slots__ = ()
    _ctype = N.pp_body

    def destroy(self) -> None:
        """Destroy the body; its handle becomes stale."""
        self._call(lib.pp_body_destroy)

    @property
    def position(self) -> Vec2:
        """World position of the pivot, (x, y) px; setting it teleports the body."""
        p = N.pp_vec2()
        self._call(lib.pp_body_get_position, byref(p))
        return p.x, p.y

    @position.setter
    def position(self, value: Vec2Like) -> None:
        self.set_transform(value, self.angle)

    @property
    def angle(self) -> float:
        """Rotation, radians (positive turns +x toward +y); setting it turns the body about its pivot."""
        a = c_float()
        self._call(lib.pp_body_get_angle, byref(a))
        return a.value

    @angle.setter
    def angle(self, value: float) -> None:
        self.set_transform(self.position, value)

    def set_transform(self, position: Vec2Like, angle: float) -> None:
        """Teleport: pivot to position (px), rotation to angle (radians); wakes the body."""
        self._call(lib.pp_body_set_transform, vec2(position, "position"), angle)

    def _velocities(self) -> Tuple[Vec2, float]:
        v, w = N.pp_vec2(), c_float()
        self._call(lib.pp_body_get_velocity, byref(v), byref(w))
        return (v.x, v.y), w.value

    @property
    def velocity(self) -> Vec2:
        """Velocity of the centre of mass, (x, y) px/s."""
        return self._velocities()[0]

    @velocity.setter
    def velocity(self, value: Vec2Like) -> None:
        self.set_velocity(value, self._velocities()[1])

    @property
    def angular_velocity(self) -> float:
        """Angular velocity, rad/s."""
        return self._velocities()[1]

    @angular_velocity.setter
    def angular_velocity(self, value: float) -> None:
        self.set_velocity(self._velocities()[0], value)

    def set_velocity(self, linear: Vec2Like, angular: float) -> None:
        """Set the centre of mass velocity (px/s) and angular velocity (rad/s); wakes the body."""
        self._call(lib.pp_body_set_velocity, vec2(linear, "linear"), angular)

    def apply_impulse(self, impulse: Vec2Like, point: Vec2Like) -> None:
        """Apply an impulse (mass·px/s) at a world point (px); dynamic bodies only."""
        self._call(lib.pp_body_apply_impulse, vec2(impulse, "impulse"), vec2(point, "point"))

    def apply_force(self, force: Vec2Like, point: Vec2Like) -> None:
        """Apply a force (mass·px/s²) at a world point (px) through the next step; dynamic bodies only."""
        self._call(lib.pp_body_apply_force, vec2(force, "force"), vec2(point, "point"))

    def apply_torque(self, torque: float) -> None:
        """Apply a torque (mass·px²/s²) through the next step; dynamic bodies only."""
        self._call(lib.pp_body_apply_torque, torque)

    def apply_angular_impulse(self, impulse: float) -> None:
        """Change the angular velocity by impulse / inertia (mass·px²/s) now; dynamic bodies only."""
        self._call(lib.pp_body_apply_angular_impulse, impulse)

    @property
    def memory(self) -> Tuple[int, int]:
        """Bytes the body holds: (collision raster, sprite copy); the weight plane counts only where there is one."""
        collision, sprite = c_int64(), c_int64()
        self._call(lib.pp_body_get_memory, byref(collision), byref(sprite))
        return collision.value, sprite.value

    def _mass(self) -> Tuple[float, Vec2, float]:
        m, c, i = c_float(), N.pp_vec2(), c_float()
        self._call(lib.pp_body_get_mass, byref(m), byref(c), byref(i))
        return m.value, (c.x, c.y), i.value

    @property
    def mass(self) -> float:
        """Mass, mass units (density × Σ weight/255 over solid pixels)."""
        return self._mass()[0]

    @property
    def center_of_mass(self) -> Vec2:
        """Centre of mass in bitmap coordinates, (x, y) px from the bitmap's top-left corner."""
        return self._mass()[1]

    @property
    def inertia(self) -> float:
        """Moment of inertia about the centre of mass, mass·px²."""
        return self._mass()[2]

    @property
    def is_awake(self) -> bool:
        """Whether the body is awake (static bodies never are)."""
        awake = c_int32()
        self._call(lib.pp_body_is_awake, byref(awake))
        return bool(awake.value)

    def _float(self, getter: Callable[..., Any]) -> float:
        out = c_float()
        self._call(getter, byref(out))
        return out.value

    @property
    def friction(self) -> float:
        """Coulomb friction coefficient (≥ 0); settable: the next step uses it and what the body touches wakes."""
        return self._float(lib.pp_body_get_friction)

    @friction.setter
    def friction(self, value: float) -> None:
        self._call(lib.pp_body_set_friction, value)

    @property
    def restitution(self) -> float:
        """Restitution 0..1; settable as friction."""
        return self._float(lib.pp_body_get_restitution)

    @restitution.setter
    def restitution(self, value: float) -> None:
        self._call(lib.pp_body_set_restitution, value)

    @property
    def density(self) -> float:
        """Mass per solid pixel; settable (mass and inertia follow, the velocity stays)."""
        return self._float(lib.pp_body_get_density)

    @density.setter
    def density(self, value: float) -> None:
        self._call(lib.pp_body_set_density, value)

    @property
    def gravity_scale(self) -> float:
        """Scale of the world's gravity on this body (default 1); settable, dynamic bodies only."""
        return self._float(lib.pp_body_get_gravity_scale)

    @gravity_scale.setter
    def gravity_scale(self, value: float) -> None:
        self._call(lib.pp_body_set_gravity_scale, value)

    @property
    def awake(self) -> bool:
        """Whether the body is awake; set False to put it to sleep now (velocity zeroed), True to wake it."""
        return self.is_awake

    @awake.setter
    def awake(self, value: bool) -> None:
        self._call(lib.pp_body_set_awake, 1 if value else 0)

    def set_damping(self, linear: float, angular: float) -> None:
        """Set the velocity decay, linear and angular, as the body def's damping fields (≥ 0)."""
        self._call(lib.pp_body_set_damping, linear, angular)

    def set_filter(self, category_bits: int, mask_bits: int) -> None:
        """Set the categories the body is in and those it collides with; wakes what it touches."""
        self._call(lib.pp_body_set_filter, _c_int(category_bits, c_uint32, "category_bits"), _mask_bits(mask_bits))

    @property
    def size(self) -> Tuple[int, int]:
        """Bitmap size, (width, height) px."""
        w, h = c_int32(), c_int32()
        self._call(lib.pp_body_get_size, byref(w), byref(h))
        return w.value, h.value

    @property
    def pivot(self) -> Vec2:
        """Pivot in bitmap coordinates, (x, y) px from the bitmap's top-left corner."""
        p = N.pp_vec2()
        self._call(lib.pp_body_get_pivot, byref(p))
        return p.x, p.y

    @property
    def type(self) -> BodyType:
        """How the body moves: a BodyType."""
        t = N.c_enum()
        self._call(lib.pp_body_get_type, byref(t))
        return BodyType(t.value)

    @type.setter
    def type(self, value: Union[BodyType, int, str]) -> None:
        """Settable as a BodyType, an int or a lower-case name ("dynamic", "static", "kinematic"): the pose
        stays, a moving body keeps its velocity."""
        self._call(lib.pp_body_set_type, enum_value(BodyType, value, "type"))

    @property
    def fixed_rotation(self) -> bool:
        """Whether the body's rotation is held; settable."""
        out = c_uint32()
        self._call(lib.pp_body_get_fixed_rotation, byref(out))
        return out.value != 0

    @fixed_rotation.setter
    def fixed_rotation(self, value: bool) -> None:
        self._call(lib.pp_body_set_fixed_rotation, 1 if value else 0)

    @property
    def user_data(self) -> int:
        """The host's integer given as user_data at creation."""
        u = c_uint64()
        self._call(lib.pp_body_get_user_data, byref(u))
        return u.value

    def erase_circle(self, center: Vec2Like, radius: float) -> int:
        """Erase the pixels whose centres lie within radius px of a world point (px); returns how many."""
        changed = c_int32(0)
        self._call(lib.pp_body_erase_circle, vec2(center, "center"), radius, byref(changed))
        return changed.value

    def paint_circle(self, center: Vec2Like, radius: float, weight: int = 255) -> int:
        """Make solid, with weight 1..255, the pixels within radius px of a world point (px); returns how many changed."""
        weight = _c_int(weight, c_uint8, "weight")
        changed = c_int32(0)
        self._call(lib.pp_body_paint_circle, vec2(center, "center"), radius, weight, byref(changed))
        return changed.value

    def write_pixels(self, x: int, y: int, mask: npt.ArrayLike, weights: Optional[npt.ArrayLike] = None) -> None:
        """Overwrite the rectangle at bitmap pixel (x, y) with mask (h, w; non-zero solid) and weights (0..255)."""
        m = _mask_u8(mask)
        wt = None if weights is None else _as_u8(weights, "weights", 2)
        if wt is not None and wt.shape != m.shape:
            raise ValueError(f"weights shape {wt.shape} differs from mask shape {m.shape}")
        h, w = m.shape
        self._call(lib.pp_body_write_pixels, _c_int(x, c_int32, "x"), _c_int(y, c_int32, "y"),
                   _c_int(w, c_int32, "mask width"), _c_int(h, c_int32, "mask height"), _u8_ptr(m), _u8_ptr(wt))

    def read_mask(self) -> npt.NDArray[np.uint8]:
        """The collision mask as a (height, width) uint8 array, 1 solid, 0 empty."""
        w, h = self.size
        out = np.empty((h, w), dtype=np.uint8)
        self._call(lib.pp_body_read_mask, _u8_ptr(out), out.nbytes)
        return out

    def read_weights(self) -> npt.NDArray[np.uint8]:
        """The weight plane as a (height, width) uint8 array: 0..255 relative mass, 255 where solid without a
        weight plane, 0 where empty."""
        w, h = self.size
        out = np.empty((h, w), dtype=np.uint8)
        self._call(lib.pp_body_read_weights, _u8_ptr(out), out.nbytes)
        return out

    def read_rgba(self) -> npt.NDArray[np.uint8]:
        """The body's look as a (height, width, 4) uint8 RGBA array: its sprite where solid, clear elsewhere;
        without a sprite, solid pixels are opaque gray of their weight."""
        w, h = self.size
        out = np.empty((h, w, 4), dtype=np.uint8)
        self._call(lib.pp_body_read_rgba, _u8_ptr(out), out.nbytes)
        return out


class Joint(_InWorld):
    """A joint of a World: a value handle; equal when world and joint ids are."""

    __slots__ = ()
    _ctype = N.pp_joint

    def destroy(self) -> None:
        """Destroy the joint; its handle becomes stale."""
        self._call(lib.pp_joint_destroy)

    @property
    def type(self) -> JointType:
        """What the joint holds."""
        t = N.c_enum()
        self._call(lib.pp_joint_get_type, byref(t))
        return JointType(t.value)

    @property
    def bodies(self) -> Tuple[Optional[Body], Optional[Body]]:
        """(body_a, body_b); None for the static world. A split moves a joint to the piece holding its anchor."""
        a, b = N.pp_body(), N.pp_body()
        self._call(lib.pp_joint_get_bodies, byref(a), byref(b))
        return self._world._body(a), self._world._body(b)

    @property
    def user_data(self) -> int:
        """The host's value given at creation."""
        v = c_uint64()
        self._call(lib.pp_joint_get_user_data, byref(v))
        return v.value

    @property
    def reaction(self) -> Tuple[Vec2, float]:
        """((fx, fy) mass·px/s², torque mass·px²/s²): what the joint applied to body_b in the last substep."""
        f, t = N.pp_vec2(), c_float()
        self._call(lib.pp_joint_get_reaction, byref(f), byref(t))
        return (f.x, f.y), t.value

    @property
    def anchors(self) -> Tuple[Vec2, Vec2]:
        """(anchor_a, anchor_b): where the joint holds each body, world px at the bodies' current poses (the static
        world's: the point it was given; MOUSE: anchor_a is the target)."""
        a, b = N.pp_vec2(), N.pp_vec2()
        self._call(lib.pp_joint_get_anchors, byref(a), byref(b))
        return (a.x, a.y), (b.x, b.y)

    @property
    def value(self) -> Tuple[float, float]:
        """(value, speed): REVOLUTE b's angle from a since creation (rad, rad/s); PRISMATIC, WHEEL its translation
        (px, px/s); DISTANCE the anchors' distance (px, px/s); others (0, 0)."""
        v, s = c_float(), c_float()
        self._call(lib.pp_joint_get_value, byref(v), byref(s))
        return v.value, s.value

    def set_motor(self, enabled: bool, speed: float = 0.0, max_force: float = 0.0) -> None:
        """REVOLUTE, WHEEL's spin (rad/s, torque mass·px²/s²), PRISMATIC or DISTANCE's length (px/s, mass·px/s²):
        drive toward speed."""
        self._call(lib.pp_joint_set_motor, 1 if enabled else 0, speed, max_force)

    def set_limits(self, enabled: bool, lower: float = 0.0, upper: float = 0.0) -> None:
        """REVOLUTE (rad, within −π..π), PRISMATIC (px) or DISTANCE (min and max length, px)."""
        self._call(lib.pp_joint_set_limits, 1 if enabled else 0, lower, upper)

    def set_target(self, target: Vec2Like) -> None:
        """MOUSE: the world point (px) the body's anchor is pulled to."""
        self._call(lib.pp_joint_set_target, vec2(target, "target"))

    def set_spring(self, hertz: float, damping_ratio: float, target: float = 0.0) -> None:
        """REVOLUTE, PRISMATIC (toward target: rad within −π..π, px), WHEEL, DISTANCE, WELD (translation): the
        spring, Hz ≥ 0 (0 rigid or none), and its damping ratio ≥ 0."""
        self._call(lib.pp_joint_set_spring, hertz, damping_ratio, target)

    def set_offsets(self, linear: Vec2Like, angular: float) -> None:
        """MOTOR: drive body_b's centre of mass to linear (px, in a's frame from a's centre of mass) and its angle
        to angular (rad) from a's."""
        self._call(lib.pp_joint_set_offsets, vec2(linear, "linear"), angular)
