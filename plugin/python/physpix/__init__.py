"""PhysPix for Python: 2D rigid bodies whose shapes are bitmaps, through ctypes and the C ABI.

Names mirror include/physpix.h: World(**pp_world_def fields), world.create_body(mask=…, **pp_body_def fields).
Units: pixels, seconds, radians; world y points down. The library is found through PHYSPIX_LIBRARY,
the copy an installed package carries, a source checkout's build/ folder, or the system's library path.
"""

from typing import Callable, Optional

from . import _native
from .enums import (CELL_A, CELL_B, CELL_CRITICAL, DEBUG_DRAW_AABBS, DEBUG_DRAW_ALL, DEBUG_DRAW_CENTERS,
                    DEBUG_DRAW_CONTACTS, DEBUG_DRAW_JOINTS, DEBUG_DRAW_OUTLINES, DEBUG_DRAW_VELOCITIES, Backend, BodyType,
                    ContactMode, DebugKind, EditType, EventType, JointType, NormalMethod, Preset, Status)
from .errors import (AbiError, FormatError, IntegerRangeError, InvalidArgumentError, InvalidHandleError, LimitError,
                     OutOfMemoryError, PhysPixError, PhysPixIOError, UnsupportedError)
from .image import image_info, load_png, save_png
from .world import (Body, Camera, CharacterMove, CollisionView, Contact, Event, Joint, RaycastHit, ScheduledEdit,
                    StepStats, World)

#: Version of the loaded library, (major, minor, patch).
library_version = (_native.version // 10000, _native.version // 100 % 100, _native.version % 100)
#: Path of the loaded libphyspix.
library_path: str = _native.path

try:  # written by setup.py from include/physpix.h when the package is built
    from ._version import version as __version__
except ImportError:  # run from a checkout: the checkout's library is built from the same header
    __version__ = "%d.%d.%d" % library_version

_log_hook = None  # the ctypes callback must outlive its installation


def set_log_hook(fn: "Optional[Callable[[int, str], None]]") -> None:
    """Install fn(level, message) as the library's log hook (0 debug … 3 error); None removes it."""
    global _log_hook
    if fn is None:
        _native.lib.pp_set_log_hook(_native.pp_log_fn(), None)
        _log_hook = None
        return
    _log_hook = _native.pp_log_fn(lambda level, msg, user: fn(level, msg.decode("utf-8", "replace")))
    _native.lib.pp_set_log_hook(_log_hook, None)


__all__ = [
    "World", "Body", "Joint", "Contact", "Event", "RaycastHit", "CharacterMove", "StepStats", "Camera", "ScheduledEdit", "CollisionView",
    "load_png", "save_png", "image_info", "set_log_hook",
    "Backend", "BodyType", "ContactMode", "EditType", "EventType", "JointType", "NormalMethod", "Preset", "Status",
    "CELL_A", "CELL_B", "CELL_CRITICAL", "DebugKind", "DEBUG_DRAW_OUTLINES", "DEBUG_DRAW_AABBS", "DEBUG_DRAW_CONTACTS",
    "DEBUG_DRAW_JOINTS", "DEBUG_DRAW_CENTERS", "DEBUG_DRAW_VELOCITIES", "DEBUG_DRAW_ALL",
    "PhysPixError", "InvalidArgumentError", "InvalidHandleError", "OutOfMemoryError", "PhysPixIOError",
    "FormatError", "UnsupportedError", "LimitError", "AbiError", "IntegerRangeError", "library_version",
    "library_path",
]
