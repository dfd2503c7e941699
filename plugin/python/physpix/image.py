"""PNG loading through the library's libpng reader (pp_image_info, pp_image_load)."""
import os
from ctypes import byref, c_int32

import numpy as np

from . import _native as N


def image_info(path):
    """Size of a PNG file's image, (width, height) px, read from its header."""
    w, h = c_int32(), c_int32()
    N.lib.pp_image_info(os.fsencode(path), byref(w), byref(h))
    return w.value, h.value


def load_png(path):
    """Decode a PNG file (any colour type, 8 or 16 bit) into a (height, width, 4) uint8 RGBA array."""
    w, h = image_info(path)
    out = np.empty((h, w, 4), dtype=np.uint8)
    got_w, got_h = c_int32(), c_int32()
    # If the file changed since the header was read, the library refuses the short buffer (InvalidArgumentError).
    N.lib.pp_image_load(os.fsencode(path), out.ctypes.data_as(N.u8p), out.nbytes, byref(got_w), byref(got_h))
    return out
