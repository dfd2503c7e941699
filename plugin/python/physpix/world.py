"""World and Body: the C ABI's calls as methods and properties, numpy arrays in and out.

Units everywhere: pixels, seconds, radians; world y points down. Every failing call raises
the PhysPixError subclass of its status with the library's message.
"""
import os
import weakref
from ctypes import POINTER, byref, c_double, c_float, c_int32, c_int64, c_uint64
from dataclasses import astuple, dataclass, fields as dataclass_fields

import numpy as np

from . import _native as N
from .enums import Backend, BodyType, ContactMode, EditType, EventType, NormalMethod, Preset
from .errors import InvalidArgumentError, PhysPixError

lib = N.lib

# Def fields that take an enum: the enum class accepts members, ints and lower-case names.
_ENUM_FIELDS = {"backend": Backend, "normal_method": NormalMethod, "contact_mode": ContactMode, "type": BodyType}
# Body def fields that create_body fills from the numpy arrays, never from keywords.
_PLANE_FIELDS = ("rgba", "mask", "weights")


def enum_value(cls, value, what):
    """An enum member from a member, an int or a case-insensitive name such as "area_gradient"."""
    if isinstance(value, str):
        try:
            return cls[value.upper()]
        except KeyError:
            choices = ", ".join(repr(m.name.lower()) for m in cls)
            raise ValueError(f"{what}: {value!r} is not one of {choices}") from None
    try:
        return cls(value)
    except ValueError:
        choices = ", ".join(f"{m.name.lower()!r} ({int(m)})" for m in cls)
        raise ValueError(f"{what}: {value!r} is not one of {choices}") from None


def vec2(value, what="vector"):
    """A pp_vec2 from any (x, y) pair of numbers."""
    try:
        x, y = value
        return N.pp_vec2(float(x), float(y))
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected an (x, y) pair of numbers, got {value!r}") from None


def _fill_def(struct, values, caller, skip=()):
    """Set def fields from keywords named as in the C struct; unknown names are a TypeError."""
    types = dict(struct._fields_)
    for name, value in values.items():
        if name in skip:
            raise TypeError(f"{caller}(): {name!r} comes from the arrays, not from a keyword")
        if name not in types:
            raise TypeError(f"{caller}() got an unexpected keyword argument {name!r}")
        if name in _ENUM_FIELDS:
            value = enum_value(_ENUM_FIELDS[name], value, name)
        elif types[name] is N.pp_vec2:
            value = vec2(value, name)
        try:
            setattr(struct, name, value)
        except TypeError as exc:  # ctypes' own message does not say which field
            raise TypeError(f"{name}: {exc}") from None


def _read_list(fn, item_type, *args, guess=0):
    """All items of a snapshot getter (bodies, contacts, collide): read with a first guess of the count
    (0: just ask it), then again with the total the library reported if that was more."""
    capacity, count = guess, c_int32(0)
    while True:
        buf = (item_type * capacity)() if capacity else None
        fn(*args, buf, capacity, byref(count))
        if count.value <= capacity:
            return list(buf[:count.value]) if capacity else []
        capacity = count.value


def _as_u8(array, name, ndim, channels=None):
    """A C-contiguous uint8 copy-free view where possible; integer arrays must hold 0..255."""
    a = np.asarray(array)
    if a.ndim != ndim or (channels is not None and a.shape[-1] != channels):
        want = "(height, width, 4)" if channels else "(height, width)"
        raise ValueError(f"{name}: expected an array of shape {want}, got shape {a.shape}")
    if a.dtype != np.uint8:
        if a.dtype.kind not in "iu" or (a.size and (a.min() < 0 or a.max() > 255)):
            raise ValueError(f"{name}: expected uint8 values 0..255, got dtype {a.dtype}")
        a = a.astype(np.uint8)
    return np.ascontiguousarray(a)


def _mask_u8(mask):
    """A collision mask as C-contiguous uint8: any dtype, non-zero is solid."""
    m = np.asarray(mask)
    if m.ndim != 2:
        raise ValueError(f"mask: expected an array of shape (height, width), got shape {m.shape}")
    return np.ascontiguousarray(m != 0, dtype=np.uint8)


_INT32 = (-2**31, 2**31 - 1)


def _check_range(value, low, high, what):
    """value as an int within low..high: the range a C integer argument holds, where ctypes would wrap it."""
    if not low <= int(value) <= high:
        raise ValueError(f"{what}: {value!r} is outside {low}..{high}")
    return int(value)


def _mask_bits(bits):
    """Collision filter bits as the uint32 the library takes, where ctypes would wrap a wider value."""
    return _check_range(bits, 0, 2**32 - 1, "mask_bits")


def _u8_ptr(array):
    return None if array is None else array.ctypes.data_as(N.u8p)


def _planes(mask, rgba, weights):
    """Validated planes and their common (height, width); a disagreement between them is a ValueError."""
    planes = {}
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
    a: "Body"
    b: "Body"
    point: tuple
    normal: tuple
    depth: float
    pixel_count: int
    normal_impulse: float


@dataclass(frozen=True)
class Event:
    """Something that happened to a body (SPLIT: other is the new body; DESTROYED: other is None; CONTACT_*:
    other is the body touched; SENSOR_*: body is the sensor, other the body overlapping it). CONTACT_BEGIN and
    SENSOR_BEGIN also give the first contact's world point (px), the unit normal from body to other, and the
    speed at which they closed along it (px/s); other events give zeros."""
    type: EventType
    body: "Body"
    other: "Body | None"
    point: tuple
    normal: tuple
    approach_speed: float


@dataclass(frozen=True)
class RaycastHit:
    """The nearest solid pixel a ray meets: the body, the world point where the ray enters it (px), the unit
    surface normal there (out of the body), and where along from → to it lies (0..1)."""
    body: "Body"
    point: tuple
    normal: tuple
    fraction: float


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
    center: tuple
    zoom: float
    width: int
    height: int


@dataclass(frozen=True)
class ScheduledEdit:
    """A pending timed edit: world time (s), circle centre (px) and radius (px); body None erases every body."""
    time: float
    type: EditType
    body: "Body | None"
    center: tuple
    radius: float
    weight: int


@dataclass(frozen=True)
class CollisionView:
    """A pair's sampled grid: size (cells), world centre of cell (0, 0) and the steps along x and y (px),
    the global normal from a to b (zero when apart), and the intersection and critical cell counts."""
    width: int
    height: int
    origin: tuple
    step_x: tuple
    step_y: tuple
    normal: tuple
    intersection: int
    critical: int


def _destroy_world(world_id):
    """Finalizer of a World never closed: destroy it, quietly (at exit nobody can handle an error)."""
    try:
        lib.pp_world_destroy(N.pp_world(world_id))
    except PhysPixError:
        pass


class World:
    """A physics world; keywords are pp_world_def field names (gravity=(0, 980) px/s², backend="cpu", …)."""

    def __init__(self, **fields):
        self._create(lib.pp_world_def_default(), fields, "World")

    @classmethod
    def from_preset(cls, preset, **fields):
        """A world from a preset ("fast", "balanced" = the default, "accurate"); keywords override its fields."""
        world = cls.__new__(cls)
        world._create(lib.pp_world_def_preset(enum_value(Preset, preset, "preset")), fields, "from_preset")
        return world

    def _create(self, d, fields, caller):
        _fill_def(d, fields, caller)
        handle = N.pp_world()
        lib.pp_world_create(byref(d), byref(handle))
        self._adopt(handle)

    def _adopt(self, handle):
        self._handle = handle
        self._finalizer = weakref.finalize(self, _destroy_world, handle.id)

    @classmethod
    def _created_by(cls, fn, path):
        world = cls.__new__(cls)
        handle = N.pp_world()
        fn(os.fsencode(path), byref(handle))
        world._adopt(handle)
        return world

    @classmethod
    def load_scene(cls, path):
        """A world from a JSON scene file (settings, camera, bodies, timed edits); PNG paths are relative to it."""
        return cls._created_by(lib.pp_world_load_scene, path)

    @classmethod
    def load_snapshot(cls, folder):
        """A world from a snapshot folder; stepping it continues exactly as the saved world would have."""
        return cls._created_by(lib.pp_world_load_snapshot, folder)

    def save_snapshot(self, folder):
        """Write the world's whole state into a new folder (world.json and PNG planes)."""
        lib.pp_world_save_snapshot(self._handle, os.fsencode(folder))

    def close(self):
        """Destroy the world and its bodies; later calls with it raise InvalidHandleError. Idempotent."""
        if self._finalizer.detach() is not None:
            lib.pp_world_destroy(self._handle)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        state = "closed" if not self._finalizer.alive else "open"
        return f"<physpix.World id={self._handle.id:#x} {state}>"

    @property
    def id(self):
        """The opaque pp_world handle value."""
        return self._handle.id

    def _body(self, handle):
        return Body(self, handle.id) if handle.id else None

    def step(self, dt):
        """Advance the world by dt seconds (0 < dt ≤ 1)."""
        lib.pp_world_step(self._handle, dt)

    def create_body(self, mask=None, rgba=None, weights=None, **fields):
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

    def bodies(self):
        """Every live body."""
        return [Body(self, h.id) for h in _read_list(lib.pp_world_get_bodies, N.pp_body, self._handle)]

    def _contacts(self, raw):
        return [Contact(Body(self, c.a.id), Body(self, c.b.id), (c.point.x, c.point.y), (c.normal.x, c.normal.y),
                        c.depth, c.pixel_count, c.normal_impulse) for c in raw]

    def contacts(self):
        """The contacts of the last substep."""
        return self._contacts(_read_list(lib.pp_world_get_contacts, N.pp_contact, self._handle))

    def collide(self, a, b):
        """Run the narrowphase on one pair at the current poses, without stepping; normals point from a to b."""
        # A pair makes at most two contacts (MANIFOLD): one call, not a count then a read of the narrowphase.
        return self._contacts(_read_list(lib.pp_world_collide, N.pp_contact, self._handle, a._handle, b._handle,
                                         guess=4))

    def events(self):
        """The events since they were last read, oldest first; reading forgets them."""
        out = []
        count = c_int32(0)
        lib.pp_world_get_events(self._handle, None, 0, byref(count))
        # Reading consumes what it writes, so read until nothing is pending rather than re-asking a total.
        while count.value > 0:
            buf = (N.pp_event * count.value)()
            lib.pp_world_get_events(self._handle, buf, count.value, byref(count))
            written = min(count.value, len(buf))
            out += [Event(EventType(e.type), Body(self, e.body.id), self._body(e.other), (e.point.x, e.point.y),
                          (e.normal.x, e.normal.y), e.approach_speed) for e in buf[:written]]
            count.value -= written
        return out

    def raycast(self, from_, to, mask_bits=0xffffffff):
        """The nearest solid pixel on the segment from → to (world px) of a body whose category_bits meet
        mask_bits (sensors skipped), as a RaycastHit, or None; a ray starting inside a solid pixel hits at 0."""
        hit, out = c_int32(0), N.pp_raycast_hit()
        lib.pp_world_raycast(self._handle, vec2(from_, "from_"), vec2(to, "to"), _mask_bits(mask_bits), byref(out),
                             byref(hit))
        if not hit.value:
            return None
        return RaycastHit(Body(self, out.body.id), (out.point.x, out.point.y), (out.normal.x, out.normal.y),
                          out.fraction)

    def _query(self, fn, *args):
        return [Body(self, h.id) for h in _read_list(fn, N.pp_body, self._handle, *args)]

    def query_point(self, point, mask_bits=0xffffffff):
        """Bodies (category_bits meeting mask_bits, sensors skipped) with a solid pixel whose square contains
        the world point (px), in slot order."""
        return self._query(lib.pp_world_query_point, vec2(point, "point"), _mask_bits(mask_bits))

    def query_aabb(self, lower, upper, mask_bits=0xffffffff):
        """Bodies with a solid pixel whose centre lies in the world box [lower, upper] (px), as query_point."""
        return self._query(lib.pp_world_query_aabb, vec2(lower, "lower"), vec2(upper, "upper"),
                           _mask_bits(mask_bits))

    def query_circle(self, center, radius, mask_bits=0xffffffff):
        """Bodies with a solid pixel whose centre lies within radius px of a world point (px), as query_point:
        the bodies erase_circle would change."""
        return self._query(lib.pp_world_query_circle, vec2(center, "center"), radius, _mask_bits(mask_bits))

    def stats(self):
        """Statistics of the last step."""
        s = N.pp_step_stats()
        lib.pp_world_get_stats(self._handle, byref(s))
        values = {f.name: getattr(s, f.name) for f in dataclass_fields(StepStats)}
        values["backend"] = Backend(values["backend"])
        return StepStats(**values)

    def erase_circle(self, center, radius):
        """Erase every body's pixels within radius px of a world point (px); returns the pixels erased."""
        changed = c_int32(0)
        lib.pp_world_erase_circle(self._handle, vec2(center, "center"), radius, byref(changed))
        return changed.value

    @property
    def time(self):
        """Simulated time since the world was created, s (the sum of every step's dt)."""
        t = c_double()
        lib.pp_world_get_time(self._handle, byref(t))
        return t.value

    @property
    def contact_events(self):
        """Whether CONTACT_BEGIN/END events are queued (the world def's contact_events); settable."""
        return bool(self.settings["contact_events"])

    @contact_events.setter
    def contact_events(self, enabled):
        lib.pp_world_set_contact_events(self._handle, 1 if enabled else 0)

    @property
    def settings(self):
        """The pp_world_def the world runs with, as a dict of field name to value (vectors as (x, y))."""
        d = N.pp_world_def()
        lib.pp_world_get_def(self._handle, byref(d))
        out = {}
        for name, _ in d._fields_[1:]:
            v = getattr(d, name)
            out[name] = (v.x, v.y) if isinstance(v, N.pp_vec2) else _ENUM_FIELDS[name](v) if name in _ENUM_FIELDS else v
        return out

    @property
    def camera(self):
        """The world's Camera (a scene's, or the default); set a Camera or (center px, zoom, width px, height px)."""
        c = N.pp_camera()
        lib.pp_world_get_camera(self._handle, byref(c))
        return Camera((c.center.x, c.center.y), c.zoom, c.width, c.height)

    @camera.setter
    def camera(self, value):
        center, zoom, width, height = astuple(value) if isinstance(value, Camera) else value
        c = N.pp_camera(vec2(center, "center"), zoom, _check_range(width, *_INT32, "width"),
                        _check_range(height, *_INT32, "height"))
        lib.pp_world_set_camera(self._handle, byref(c))

    def _schedule(self, time, edit_type, body, center, radius, weight):
        e = N.pp_timed_edit(time=time, type=edit_type, weight=weight, center=vec2(center, "center"), radius=radius)
        e.body = body._handle if body is not None else N.pp_body()
        lib.pp_world_schedule_edit(self._handle, byref(e))

    def schedule_erase(self, time, center, radius, body=None):
        """Erase at world time (s) the pixels within radius px of a world point (px): of body, or of every body."""
        self._schedule(time, EditType.ERASE_CIRCLE, body, center, radius, 0)

    def schedule_paint(self, time, body, center, radius, weight=255):
        """Make solid at world time (s), with weight 1..255, body's pixels within radius px of a world point (px)."""
        # As in paint_circle: ctypes would wrap -1 or 2**32 in the 32-bit field; the library refuses 0 itself.
        self._schedule(time, EditType.PAINT_CIRCLE, body, center, radius, _check_range(weight, 0, 255, "weight"))

    def scheduled_edits(self):
        """The edits still pending, in the order they will apply."""
        return [ScheduledEdit(e.time, EditType(e.type), self._body(e.body), (e.center.x, e.center.y), e.radius,
                              e.weight)
                for e in _read_list(lib.pp_world_get_scheduled_edits, N.pp_timed_edit, self._handle)]

    def debug_collision(self, a, b):
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


class Body:
    """A body of a World: a value handle; equal when world and body ids are."""

    __slots__ = ("_world", "_handle")

    def __init__(self, world, body_id):
        self._world = world
        self._handle = N.pp_body(body_id)

    def __eq__(self, other):
        return isinstance(other, Body) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def _key(self):
        return self._world._handle.id, self._handle.id

    def __repr__(self):
        return f"<physpix.Body id={self._handle.id:#x}>"

    def _call(self, fn, *args):
        return fn(self._world._handle, self._handle, *args)

    @property
    def world(self):
        """The World the body lives in."""
        return self._world

    @property
    def id(self):
        """The opaque pp_body handle value."""
        return self._handle.id

    def destroy(self):
        """Destroy the body; its handle becomes stale."""
        self._call(lib.pp_body_destroy)

    @property
    def position(self):
        """World position of the pivot, (x, y) px; setting it teleports the body."""
        p = N.pp_vec2()
        self._call(lib.pp_body_get_position, byref(p))
        return p.x, p.y

    @position.setter
    def position(self, value):
        self.set_transform(value, self.angle)

    @property
    def angle(self):
        """Rotation, radians (positive turns +x toward +y); setting it turns the body about its pivot."""
        a = c_float()
        self._call(lib.pp_body_get_angle, byref(a))
        return a.value

    @angle.setter
    def angle(self, value):
        self.set_transform(self.position, value)

    def set_transform(self, position, angle):
        """Teleport: pivot to position (px), rotation to angle (radians); wakes the body."""
        self._call(lib.pp_body_set_transform, vec2(position, "position"), angle)

    def _velocities(self):
        v, w = N.pp_vec2(), c_float()
        self._call(lib.pp_body_get_velocity, byref(v), byref(w))
        return (v.x, v.y), w.value

    @property
    def velocity(self):
        """Velocity of the centre of mass, (x, y) px/s."""
        return self._velocities()[0]

    @velocity.setter
    def velocity(self, value):
        self.set_velocity(value, self._velocities()[1])

    @property
    def angular_velocity(self):
        """Angular velocity, rad/s."""
        return self._velocities()[1]

    @angular_velocity.setter
    def angular_velocity(self, value):
        self.set_velocity(self._velocities()[0], value)

    def set_velocity(self, linear, angular):
        """Set the centre of mass velocity (px/s) and angular velocity (rad/s); wakes the body."""
        self._call(lib.pp_body_set_velocity, vec2(linear, "linear"), angular)

    def apply_impulse(self, impulse, point):
        """Apply an impulse (mass·px/s) at a world point (px); dynamic bodies only."""
        self._call(lib.pp_body_apply_impulse, vec2(impulse, "impulse"), vec2(point, "point"))

    @property
    def memory(self):
        """Bytes the body holds: (collision raster, sprite copy); the weight plane counts only where there is one."""
        collision, sprite = c_int64(), c_int64()
        self._call(lib.pp_body_get_memory, byref(collision), byref(sprite))
        return collision.value, sprite.value

    def _mass(self):
        m, c, i = c_float(), N.pp_vec2(), c_float()
        self._call(lib.pp_body_get_mass, byref(m), byref(c), byref(i))
        return m.value, (c.x, c.y), i.value

    @property
    def mass(self):
        """Mass, mass units (density × Σ weight/255 over solid pixels)."""
        return self._mass()[0]

    @property
    def center_of_mass(self):
        """Centre of mass in bitmap coordinates, (x, y) px from the bitmap's top-left corner."""
        return self._mass()[1]

    @property
    def inertia(self):
        """Moment of inertia about the centre of mass, mass·px²."""
        return self._mass()[2]

    @property
    def is_awake(self):
        """Whether the body is awake (static bodies never are)."""
        awake = c_int32()
        self._call(lib.pp_body_is_awake, byref(awake))
        return bool(awake.value)

    @property
    def size(self):
        """Bitmap size, (width, height) px."""
        w, h = c_int32(), c_int32()
        self._call(lib.pp_body_get_size, byref(w), byref(h))
        return w.value, h.value

    @property
    def pivot(self):
        """Pivot in bitmap coordinates, (x, y) px from the bitmap's top-left corner."""
        p = N.pp_vec2()
        self._call(lib.pp_body_get_pivot, byref(p))
        return p.x, p.y

    @property
    def type(self):
        """How the body moves: a BodyType."""
        t = N.c_enum()
        self._call(lib.pp_body_get_type, byref(t))
        return BodyType(t.value)

    @property
    def user_data(self):
        """The host's integer given as user_data at creation."""
        u = c_uint64()
        self._call(lib.pp_body_get_user_data, byref(u))
        return u.value

    def erase_circle(self, center, radius):
        """Erase the pixels whose centres lie within radius px of a world point (px); returns how many."""
        changed = c_int32(0)
        self._call(lib.pp_body_erase_circle, vec2(center, "center"), radius, byref(changed))
        return changed.value

    def paint_circle(self, center, radius, weight=255):
        """Make solid, with weight 1..255, the pixels within radius px of a world point (px); returns how many changed."""
        # c_uint8 would wrap 256 to 0 silently; the library cannot see what was meant.
        if not 0 <= int(weight) <= 255:
            raise ValueError(f"weight: {weight!r} is outside 0..255")
        changed = c_int32(0)
        self._call(lib.pp_body_paint_circle, vec2(center, "center"), radius, weight, byref(changed))
        return changed.value

    def write_pixels(self, x, y, mask, weights=None):
        """Overwrite the rectangle at bitmap pixel (x, y) with mask (h, w; non-zero solid) and weights (0..255)."""
        m = _mask_u8(mask)
        wt = None if weights is None else _as_u8(weights, "weights", 2)
        if wt is not None and wt.shape != m.shape:
            raise ValueError(f"weights shape {wt.shape} differs from mask shape {m.shape}")
        h, w = m.shape
        self._call(lib.pp_body_write_pixels, x, y, w, h, _u8_ptr(m), _u8_ptr(wt))

    def read_mask(self):
        """The collision mask as a (height, width) uint8 array, 1 solid, 0 empty."""
        w, h = self.size
        out = np.empty((h, w), dtype=np.uint8)
        self._call(lib.pp_body_read_mask, _u8_ptr(out), out.nbytes)
        return out

    def read_rgba(self):
        """The body's look as a (height, width, 4) uint8 RGBA array: its sprite where solid, clear elsewhere;
        without a sprite, solid pixels are opaque gray of their weight."""
        w, h = self.size
        out = np.empty((h, w, 4), dtype=np.uint8)
        self._call(lib.pp_body_read_rgba, _u8_ptr(out), out.nbytes)
        return out
