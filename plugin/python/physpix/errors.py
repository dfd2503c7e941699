"""Exceptions: PhysPixError and one subclass per pp_status, each carrying the library's message; IntegerRangeError
for an integer the package refuses before the library sees it."""
from __future__ import annotations

from typing import Dict, Optional, Type, Union

from .enums import Status


class PhysPixError(Exception):
    """A call into libphyspix failed; .status is the pp_status, .message the library's message naming the call
    the program made (``load_png: cannot open 'x.png': ...``), .library_message pp_last_error()'s own text (which
    names the C function, ``pp_image_info: ...``)."""
    #: The pp_status (a Status, or the int of one this package does not know); None on a PhysPixError made without.
    status: Optional[Union[Status, int]] = None
    message: str
    #: The C function that failed ("pp_world_step"), or None.
    function: Optional[str]
    #: The package's call the program made ("World.step", "load_png"), or None.
    call: Optional[str]
    #: pp_last_error()'s text as the library wrote it.
    library_message: str

    def __init__(self, message: str, status: Optional[Union[Status, int]] = None,
                 function: Optional[str] = None, call: Optional[str] = None,
                 library_message: Optional[str] = None) -> None:
        super().__init__(message)
        self.message = message
        if status is not None:
            self.status = status
        self.function = function
        self.call = call
        self.library_message = message if library_message is None else library_message


class InvalidArgumentError(PhysPixError):
    """PP_ERR_INVALID_ARGUMENT: NULL, NaN, out-of-range or inconsistent argument."""
    status = Status.INVALID_ARGUMENT


class InvalidHandleError(PhysPixError):
    """PP_ERR_INVALID_HANDLE: a null, destroyed or stale world or body handle."""
    status = Status.INVALID_HANDLE


class OutOfMemoryError(PhysPixError):
    """PP_ERR_OUT_OF_MEMORY: an allocation failed; nothing was changed."""
    status = Status.OUT_OF_MEMORY


class PhysPixIOError(PhysPixError):
    """PP_ERR_IO: a file could not be read or written."""
    status = Status.IO


class FormatError(PhysPixError):
    """PP_ERR_FORMAT: a file's contents are malformed."""
    status = Status.FORMAT


class UnsupportedError(PhysPixError):
    """PP_ERR_UNSUPPORTED: the feature is not available here (e.g. no GPU)."""
    status = Status.UNSUPPORTED


class LimitError(PhysPixError):
    """PP_ERR_LIMIT: a size over the documented PP_MAX_* limits."""
    status = Status.LIMIT


class AbiError(PhysPixError):
    """PP_ERR_ABI: a def struct whose struct_size does not match the library."""
    status = Status.ABI


class IntegerRangeError(OverflowError, ValueError):
    """An integer argument or def field outside the range of the C type it reaches, where ctypes would wrap it
    silently; raised before the library is called. An OverflowError as Python's own conversions raise, and a
    ValueError so that `except ValueError` around a bad argument catches it too."""


_BY_STATUS: Dict[Optional[Union[Status, int]], Type[PhysPixError]] = {
    cls.status: cls for cls in (InvalidArgumentError, InvalidHandleError, OutOfMemoryError, PhysPixIOError, FormatError,
                                UnsupportedError, LimitError, AbiError)}


def error_for(status: int, message: Optional[str], function: str, name: str,
              call: Optional[str] = None) -> PhysPixError:
    """The exception for a failed call: its status's subclass (PhysPixError for an unknown status). The library's
    message starts with the C function's name; with call (the package's call the program made) it names that."""
    try:
        status = Status(status)
    except ValueError:
        status = int(status)
    if not message:  # the library promises a message; never raise an empty one
        message = f"{function} failed with {name}"
    shown = message
    if call:
        shown = call + message[len(function):] if message.startswith(function + ":") else f"{call}: {message}"
    return _BY_STATUS.get(int(status), PhysPixError)(shown, status, function, call, message)
