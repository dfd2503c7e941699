"""Loading libphyspix, binding its signatures and the status checker.

The ctypes mirror of include/physpix.h (structs, callbacks, SIGNATURES) is _api.py, generated from
plugin/api/physpix_api.json; the friendly classes live in world.py and image.py.
"""
import ctypes
import os
import sys
import threading
from ctypes.util import find_library
from pathlib import Path

from .enums import Status
from .errors import error_for

# The structs, callbacks and signatures are generated from plugin/api/physpix_api.json (plugin/api/gen_api.py).
from ._api import *  # noqa: F401,F403  (re-exported: world.py reads N.pp_vec2, N.u8p, …)
from ._api import SIGNATURES, STATUS, c_enum, pp_body_def, pp_world, pp_world_def


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


_PACKAGE = __name__.rpartition(".")[0]


def python_call():
    """The package's call the program made ("load_png", "World.step", "Body.type"): the outermost frame of this
    package on the stack, as its qualified name (a constructor as its class); None when none is on it."""
    frame, found = sys._getframe(1), None
    while frame is not None:
        module = frame.f_globals.get("__name__", "")
        if module == _PACKAGE or module.startswith(_PACKAGE + "."):
            found = frame
        elif found is not None:
            break
        frame = frame.f_back
    if found is None:
        return None
    code = found.f_code
    name = getattr(code, "co_qualname", None)  # Python 3.11; before it, the class from self or cls
    if name is None:
        owner = found.f_locals.get("self", found.f_locals.get("cls"))
        owner = owner if isinstance(owner, type) or owner is None else type(owner)
        name = f"{owner.__name__}.{code.co_name}" if owner is not None else code.co_name
    return name[: -len(".__init__")] if name.endswith(".__init__") else name


def check(result, func, args):
    """ctypes errcheck of every pp_status call: a non-zero status raises its PhysPixError subclass, its message
    naming the package's call the program made rather than the C function."""
    if result != Status.OK:
        # Read at once: the message is thread-local and the next failing call overwrites it.
        raise error_for(result, last_error(), func.__name__, status_name(result), python_call())
    return result


# A World may be shared between threads, and its calls then run one at a time. The library's worlds are used from
# one thread at a time, and ctypes lets go of the GIL during a call, so two threads inside one world at once
# corrupted it (issue 39). Every call whose first argument is a pp_world holds that world's lock; different worlds
# still run in parallel. The lock is reentrant, so a log hook may call into the world whose call logged.
_world_locks = {}


def _world_lock(world_id):
    return _world_locks.get(world_id) or _world_locks.setdefault(world_id, threading.RLock())


def _one_at_a_time(fn):
    """fn, whose first argument is a pp_world, called under that world's lock."""
    def call(world, *args):
        with _world_lock(world.id):
            try:
                return fn(world, *args)
            finally:
                if fn.__name__ == "pp_world_destroy":
                    _world_locks.pop(world.id, None)  # a destroyed world's id never comes back
    call.__name__ = fn.__name__
    return call


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
    if _args and _args[0] is pp_world:
        setattr(lib, _name, _one_at_a_time(_fn))

version = lib.pp_version()
if version // 10000 != 0:
    raise ImportError(f"physpix: {path} is version {version // 10000}.{version // 100 % 100}.{version % 100}; "
                      "this package needs major version 0")
# A layout mismatch would corrupt memory silently; the library reports its struct sizes, so check them now.
for _cls, _default in ((pp_world_def, lib.pp_world_def_default), (pp_body_def, lib.pp_body_def_default)):
    if _default().struct_size != ctypes.sizeof(_cls):
        raise ImportError(f"physpix: {path} says sizeof({_cls.__name__}) is {_default().struct_size}, "
                          f"this package's mirror is {ctypes.sizeof(_cls)}")
