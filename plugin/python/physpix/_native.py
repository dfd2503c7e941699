"""The ctypes mirror of include/physpix.h: library loading, structs, signatures, the status checker.

Everything here follows the header one to one; the friendly classes live in world.py and image.py.
"""
import ctypes
import os
from ctypes import POINTER, c_char_p, c_double, c_float, c_int, c_int32, c_int64, c_uint8, c_uint32, c_uint64, c_void_p
from ctypes.util import find_library
from pathlib import Path

from .enums import Status
from .errors import error_for

# C enums forced to 32 bits (…_FORCE_U32 = 0x7fffffff) are int-sized and signed-compatible.
c_enum = c_int32


class pp_vec2(ctypes.Structure):
    _fields_ = [("x", c_float), ("y", c_float)]


class pp_world(ctypes.Structure):
    _fields_ = [("id", c_uint64)]


class pp_body(ctypes.Structure):
    _fields_ = [("id", c_uint64)]


class pp_joint(ctypes.Structure):
    _fields_ = [("id", c_uint64)]


class pp_world_def(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_uint32),
        ("gravity", pp_vec2),
        ("substeps", c_int32),
        ("solver_iterations", c_int32),
        ("exact_solver", c_uint32),
        ("backend", c_enum),
        ("normal_method", c_enum),
        ("contact_mode", c_enum),
        ("raster_stride", c_int32),
        ("pixels_per_meter", c_float),
        ("contact_slop", c_float),
        ("contact_erp", c_float),
        ("contact_cfm", c_float),
        ("bounce_threshold", c_float),
        ("allow_sleep", c_uint32),
        ("sleep_linear_speed", c_float),
        ("sleep_angular_speed", c_float),
        ("sleep_time", c_float),
        ("continuous", c_uint32),
        ("max_correction_speed", c_float),
        ("worker_threads", c_int32),
        ("contact_events", c_uint32),
        ("exact_island_rows", c_int32),
    ]


class pp_body_def(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_uint32),
        ("type", c_enum),
        ("position", pp_vec2),
        ("angle", c_float),
        ("custom_pivot", c_uint32),
        ("pivot", pp_vec2),
        ("linear_velocity", pp_vec2),
        ("angular_velocity", c_float),
        ("density", c_float),
        ("friction", c_float),
        ("restitution", c_float),
        ("linear_damping", c_float),
        ("angular_damping", c_float),
        ("category_bits", c_uint32),
        ("mask_bits", c_uint32),
        ("fixed_rotation", c_uint32),
        ("width", c_int32),
        ("height", c_int32),
        ("rgba", POINTER(c_uint8)),
        ("mask", POINTER(c_uint8)),
        ("weights", POINTER(c_uint8)),
        ("alpha_threshold", c_uint32),
        ("detach_islands", c_uint32),
        ("user_data", c_uint64),
        ("bullet", c_uint32),
        ("is_sensor", c_uint32),
        ("one_way", c_uint32),
        ("one_way_direction", pp_vec2),
    ]


class pp_contact(ctypes.Structure):
    _fields_ = [
        ("a", pp_body),
        ("b", pp_body),
        ("point", pp_vec2),
        ("normal", pp_vec2),
        ("depth", c_float),
        ("pixel_count", c_int32),
        ("normal_impulse", c_float),
        ("reserved", c_uint32),
    ]


class pp_event(ctypes.Structure):
    _fields_ = [
        ("type", c_enum),
        ("reserved", c_uint32),
        ("body", pp_body),
        ("other", pp_body),
        ("point", pp_vec2),
        ("normal", pp_vec2),
        ("approach_speed", c_float),
        ("reserved2", c_uint32),
        ("joint", pp_joint),
    ]


class pp_raycast_hit(ctypes.Structure):
    _fields_ = [
        ("body", pp_body),
        ("point", pp_vec2),
        ("normal", pp_vec2),
        ("fraction", c_float),
        ("reserved", c_uint32),
    ]


class pp_step_stats(ctypes.Structure):
    _fields_ = [
        ("broadphase_ms", c_float),
        ("narrowphase_ms", c_float),
        ("solver_ms", c_float),
        ("total_ms", c_float),
        ("bodies", c_int32),
        ("awake_bodies", c_int32),
        ("pairs", c_int32),
        ("contacts", c_int32),
        ("pixels_tested", c_int64),
        ("backend", c_enum),
        ("swept_stops", c_uint32),
        ("threads", c_int32),
    ]


class pp_camera(ctypes.Structure):
    _fields_ = [("center", pp_vec2), ("zoom", c_float), ("width", c_int32), ("height", c_int32)]


class pp_timed_edit(ctypes.Structure):
    _fields_ = [
        ("time", c_double),
        ("type", c_enum),
        ("weight", c_uint32),
        ("body", pp_body),
        ("center", pp_vec2),
        ("radius", c_float),
        ("reserved", c_uint32),
    ]


class pp_body_state(ctypes.Structure):
    _fields_ = [
        ("body", pp_body),
        ("position", pp_vec2),
        ("angle", c_float),
        ("linear_velocity", pp_vec2),
        ("angular_velocity", c_float),
        ("awake", c_uint32),
    ]


class pp_joint_def(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_uint32),
        ("type", c_enum),
        ("body_a", pp_body),
        ("body_b", pp_body),
        ("anchor_a", pp_vec2),
        ("anchor_b", pp_vec2),
        ("axis", pp_vec2),
        ("collide_connected", c_uint32),
        ("enable_limit", c_uint32),
        ("lower", c_float),
        ("upper", c_float),
        ("enable_motor", c_uint32),
        ("motor_speed", c_float),
        ("max_motor_force", c_float),
        ("min_length", c_float),
        ("max_length", c_float),
        ("spring_hertz", c_float),
        ("spring_damping_ratio", c_float),
        ("max_force", c_float),
        ("break_force", c_float),
        ("reserved", c_uint32),
        ("user_data", c_uint64),
    ]


class pp_collision_view(ctypes.Structure):
    _fields_ = [
        ("width", c_int32),
        ("height", c_int32),
        ("origin", pp_vec2),
        ("step_x", pp_vec2),
        ("step_y", pp_vec2),
        ("normal", pp_vec2),
        ("intersection", c_int32),
        ("critical", c_int32),
    ]


pp_log_fn = ctypes.CFUNCTYPE(None, c_int, c_char_p, c_void_p)
pp_alloc_fn = ctypes.CFUNCTYPE(c_void_p, c_uint64, c_void_p)
pp_realloc_fn = ctypes.CFUNCTYPE(c_void_p, c_void_p, c_uint64, c_void_p)
pp_free_fn = ctypes.CFUNCTYPE(None, c_void_p, c_void_p)


class pp_allocator(ctypes.Structure):
    _fields_ = [
        ("alloc", pp_alloc_fn),
        ("realloc", pp_realloc_fn),
        ("free", pp_free_fn),
        ("user", c_void_p),
    ]


# Every public struct, by its C name (the layout test walks this).
STRUCTS = {cls.__name__: cls for cls in
           (pp_vec2, pp_world, pp_body, pp_world_def, pp_body_def, pp_contact, pp_event, pp_raycast_hit,
            pp_step_stats, pp_camera, pp_timed_edit, pp_body_state, pp_joint, pp_joint_def, pp_collision_view,
            pp_allocator)}

STATUS = "status"  # marks a function returning pp_status: its result goes through check()
P = POINTER
u8p = P(c_uint8)

# name: (restype, argtypes), in header order.
SIGNATURES = {
    "pp_version": (c_uint32, []),
    "pp_status_name": (c_char_p, [c_enum]),
    "pp_last_error": (c_char_p, []),
    "pp_set_log_hook": (None, [pp_log_fn, c_void_p]),
    "pp_set_allocator": (STATUS, [P(pp_allocator)]),
    "pp_world_def_default": (pp_world_def, []),
    "pp_world_def_preset": (pp_world_def, [c_enum]),
    "pp_world_create": (STATUS, [P(pp_world_def), P(pp_world)]),
    "pp_world_get_def": (STATUS, [pp_world, P(pp_world_def)]),
    "pp_world_set_contact_events": (STATUS, [pp_world, c_uint32]),
    "pp_world_destroy": (STATUS, [pp_world]),
    "pp_world_step": (STATUS, [pp_world, c_float]),
    "pp_world_get_bodies": (STATUS, [pp_world, P(pp_body), c_int32, P(c_int32)]),
    "pp_world_get_contacts": (STATUS, [pp_world, P(pp_contact), c_int32, P(c_int32)]),
    "pp_world_get_stats": (STATUS, [pp_world, P(pp_step_stats)]),
    "pp_world_get_events": (STATUS, [pp_world, P(pp_event), c_int32, P(c_int32)]),
    "pp_world_erase_circle": (STATUS, [pp_world, pp_vec2, c_float, P(c_int32)]),
    "pp_world_raycast": (STATUS, [pp_world, pp_vec2, pp_vec2, c_uint32, P(pp_raycast_hit), P(c_int32)]),
    "pp_world_query_point": (STATUS, [pp_world, pp_vec2, c_uint32, P(pp_body), c_int32, P(c_int32)]),
    "pp_world_query_aabb": (STATUS, [pp_world, pp_vec2, pp_vec2, c_uint32, P(pp_body), c_int32, P(c_int32)]),
    "pp_world_query_circle": (STATUS, [pp_world, pp_vec2, c_float, c_uint32, P(pp_body), c_int32, P(c_int32)]),
    "pp_world_collide": (STATUS, [pp_world, pp_body, pp_body, P(pp_contact), c_int32, P(c_int32)]),
    "pp_body_def_default": (pp_body_def, []),
    "pp_body_create": (STATUS, [pp_world, P(pp_body_def), P(pp_body)]),
    "pp_body_destroy": (STATUS, [pp_world, pp_body]),
    "pp_body_get_position": (STATUS, [pp_world, pp_body, P(pp_vec2)]),
    "pp_body_get_angle": (STATUS, [pp_world, pp_body, P(c_float)]),
    "pp_body_set_transform": (STATUS, [pp_world, pp_body, pp_vec2, c_float]),
    "pp_body_get_velocity": (STATUS, [pp_world, pp_body, P(pp_vec2), P(c_float)]),
    "pp_body_set_velocity": (STATUS, [pp_world, pp_body, pp_vec2, c_float]),
    "pp_body_apply_impulse": (STATUS, [pp_world, pp_body, pp_vec2, pp_vec2]),
    "pp_body_get_mass": (STATUS, [pp_world, pp_body, P(c_float), P(pp_vec2), P(c_float)]),
    "pp_body_get_memory": (STATUS, [pp_world, pp_body, P(c_int64), P(c_int64)]),
    "pp_body_is_awake": (STATUS, [pp_world, pp_body, P(c_int32)]),
    "pp_body_set_friction": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_set_restitution": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_set_damping": (STATUS, [pp_world, pp_body, c_float, c_float]),
    "pp_body_set_density": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_set_filter": (STATUS, [pp_world, pp_body, c_uint32, c_uint32]),
    "pp_body_set_awake": (STATUS, [pp_world, pp_body, c_uint32]),
    "pp_body_apply_force": (STATUS, [pp_world, pp_body, pp_vec2, pp_vec2]),
    "pp_body_apply_torque": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_apply_angular_impulse": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_set_gravity_scale": (STATUS, [pp_world, pp_body, c_float]),
    "pp_body_get_friction": (STATUS, [pp_world, pp_body, P(c_float)]),
    "pp_body_get_restitution": (STATUS, [pp_world, pp_body, P(c_float)]),
    "pp_body_get_density": (STATUS, [pp_world, pp_body, P(c_float)]),
    "pp_body_get_gravity_scale": (STATUS, [pp_world, pp_body, P(c_float)]),
    "pp_world_set_gravity": (STATUS, [pp_world, pp_vec2]),
    "pp_world_get_body_states": (STATUS, [pp_world, P(pp_body_state), c_int32, P(c_int32)]),
    "pp_joint_def_default": (pp_joint_def, [c_enum]),
    "pp_joint_create": (STATUS, [pp_world, P(pp_joint_def), P(pp_joint)]),
    "pp_joint_destroy": (STATUS, [pp_world, pp_joint]),
    "pp_world_get_joints": (STATUS, [pp_world, P(pp_joint), c_int32, P(c_int32)]),
    "pp_joint_get_reaction": (STATUS, [pp_world, pp_joint, P(pp_vec2), P(c_float)]),
    "pp_joint_get_value": (STATUS, [pp_world, pp_joint, P(c_float), P(c_float)]),
    "pp_joint_set_motor": (STATUS, [pp_world, pp_joint, c_uint32, c_float, c_float]),
    "pp_joint_set_limits": (STATUS, [pp_world, pp_joint, c_uint32, c_float, c_float]),
    "pp_joint_set_target": (STATUS, [pp_world, pp_joint, pp_vec2]),
    "pp_joint_get_type": (STATUS, [pp_world, pp_joint, P(c_enum)]),
    "pp_joint_get_bodies": (STATUS, [pp_world, pp_joint, P(pp_body), P(pp_body)]),
    "pp_joint_get_user_data": (STATUS, [pp_world, pp_joint, P(c_uint64)]),
    "pp_body_erase_circle": (STATUS, [pp_world, pp_body, pp_vec2, c_float, P(c_int32)]),
    "pp_body_paint_circle": (STATUS, [pp_world, pp_body, pp_vec2, c_float, c_uint8, P(c_int32)]),
    "pp_body_write_pixels": (STATUS, [pp_world, pp_body, c_int32, c_int32, c_int32, c_int32, u8p, u8p]),
    "pp_body_read_mask": (STATUS, [pp_world, pp_body, u8p, c_int64]),
    "pp_body_get_size": (STATUS, [pp_world, pp_body, P(c_int32), P(c_int32)]),
    "pp_body_get_user_data": (STATUS, [pp_world, pp_body, P(c_uint64)]),
    "pp_image_info": (STATUS, [c_char_p, P(c_int32), P(c_int32)]),
    "pp_image_load": (STATUS, [c_char_p, u8p, c_int64, P(c_int32), P(c_int32)]),
    "pp_image_save": (STATUS, [c_char_p, u8p, c_int32, c_int32]),
    "pp_body_get_pivot": (STATUS, [pp_world, pp_body, P(pp_vec2)]),
    "pp_body_get_type": (STATUS, [pp_world, pp_body, P(c_enum)]),
    "pp_body_read_rgba": (STATUS, [pp_world, pp_body, u8p, c_int64]),
    "pp_world_get_time": (STATUS, [pp_world, P(c_double)]),
    "pp_world_get_camera": (STATUS, [pp_world, P(pp_camera)]),
    "pp_world_set_camera": (STATUS, [pp_world, P(pp_camera)]),
    "pp_world_schedule_edit": (STATUS, [pp_world, P(pp_timed_edit)]),
    "pp_world_get_scheduled_edits": (STATUS, [pp_world, P(pp_timed_edit), c_int32, P(c_int32)]),
    "pp_world_debug_collision": (STATUS, [pp_world, pp_body, pp_body, u8p, P(pp_vec2), c_int64,
                                          P(pp_collision_view)]),
    "pp_world_load_scene": (STATUS, [c_char_p, P(pp_world)]),
    "pp_world_save_snapshot": (STATUS, [pp_world, c_char_p]),
    "pp_world_load_snapshot": (STATUS, [c_char_p, P(pp_world)]),
}


def _candidates():
    """Where libphyspix may be, best first: the package's own copy, a checkout's build/, an installed prefix."""
    here = Path(__file__).resolve().parent
    yield here / "libphyspix.so"                                  # a wheel or `pip install` bundles it here
    yield here.parents[2] / "build" / "libphyspix.so"             # run from a checkout: plugin/python/physpix
    yield here.parents[3] / "lib" / "libphyspix.so.0"             # PREFIX/share/physpix/python/physpix


def _load():
    """Load libphyspix from PHYSPIX_LIBRARY, else the first of _candidates() that exists, else the system's."""
    env = os.environ.get("PHYSPIX_LIBRARY")
    if env:
        # An explicit choice is final: falling back elsewhere would hide a wrong path.
        candidates, tried = [env], []
    else:
        tried = ["PHYSPIX_LIBRARY (unset)"]
        candidates = []
        for path in _candidates():
            if path.exists():
                candidates.append(str(path))
            else:
                tried.append(f"{path} (missing)")
        system = find_library("physpix")
        if system:
            candidates.append(system)
        else:
            tried.append("ctypes.util.find_library('physpix') (nothing)")
    for candidate in candidates:
        try:
            return ctypes.CDLL(candidate), candidate
        except OSError as exc:
            tried.append(f"{candidate} ({exc})")
    raise ImportError(f"physpix: cannot load libphyspix; looked at: {'; '.join(tried)}. "
                      "Install the package with `pip install ./plugin/python`, build a checkout with `make all`, "
                      "or set PHYSPIX_LIBRARY to the .so path.")


def last_error():
    """The library's thread-local message of the last failure on this thread ("" if none)."""
    return lib.pp_last_error().decode("utf-8", "replace")


def status_name(status):
    """The library's name of a status, e.g. 'PP_ERR_LIMIT'."""
    return lib.pp_status_name(status).decode("ascii", "replace")


def check(result, func, args):
    """ctypes errcheck of every pp_status call: a non-zero status raises its PhysPixError subclass."""
    if result != Status.OK:
        # Read at once: the message is thread-local and the next failing call overwrites it.
        raise error_for(result, last_error(), func.__name__, status_name(result))
    return result


lib, path = _load()
for _name, (_res, _args) in SIGNATURES.items():
    try:
        _fn = getattr(lib, _name)
    except AttributeError:
        raise ImportError(f"physpix: {path} has no {_name}; it is older than this package") from None
    _fn.argtypes = _args
    if _res is STATUS:
        _fn.restype = c_enum
        _fn.errcheck = check
    else:
        _fn.restype = _res

version = lib.pp_version()
if version // 10000 != 0:
    raise ImportError(f"physpix: {path} is version {version // 10000}.{version // 100 % 100}.{version % 100}; "
                      "this package needs major version 0")
# A layout mismatch would corrupt memory silently; the library reports its struct sizes, so check them now.
for _cls, _default in ((pp_world_def, lib.pp_world_def_default), (pp_body_def, lib.pp_body_def_default)):
    if _default().struct_size != ctypes.sizeof(_cls):
        raise ImportError(f"physpix: {path} says sizeof({_cls.__name__}) is {_default().struct_size}, "
                          f"this package's mirror is {ctypes.sizeof(_cls)}")
