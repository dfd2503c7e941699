"""PNG files through the library's libpng reader and writer (pp_image_info, pp_image_load, pp_image_save)."""
from __future__ import annotations

from ctypes import byref, c_int32
from typing import Tuple

import numpy as np

from . import _native as N
from .world import PathLike, _as_u8, _c_int, _path

try:  # the array hints' names, so that typing.get_type_hints resolves them (numpy.typing.NDArray: numpy >= 1.21)
    import numpy.typing as npt
except ImportError:  # an older numpy runs the package all the same; only its hints do not resolve at run time
    pass


def image_info(path: PathLike) -> Tuple[int, int]:
    """Size of a PNG file's image, (width, height) px, read from its header."""
    w, h = c_int32(), c_int32()
    N.lib.pp_image_info(_path(path, "path"), byref(w), byref(h))
    return w.value, h.value


def load_png(path: PathLike) -> npt.NDArray[np.uint8]:
    """Decode a PNG file (any colour type, 8 or 16 bit) into a (height, width, 4) uint8 RGBA array."""
    w, h = image_info(path)
    out = np.empty((h, w, 4), dtype=np.uint8)
    got_w, got_h = c_int32(), c_int32()
    # If the file changed since the header was read, the library refuses the short buffer (InvalidArgumentError).
    N.lib.pp_image_load(_path(path, "path"), out.ctypes.data_as(N.u8p), out.nbytes, byref(got_w), byref(got_h))
    return out


def save_png(path: PathLike, rgba: npt.ArrayLike) -> None:
    """Encode a (height, width, 4) RGBA array (uint8, or integers 0..255) as an 8-bit RGBA PNG file."""
    a = _as_u8(rgba, "rgba", 3, channels=4)
    encoded = _path(path, "path")
    N.lib.pp_image_save(encoded, a.ctypes.data_as(N.u8p), _c_int(a.shape[1], c_int32, "rgba width"),
                        _c_int(a.shape[0], c_int32, "rgba height"))
