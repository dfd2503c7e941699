"""Small helpers of the Python tests: solid rectangles, angles, PNG files written by hand (zlib + struct),
and the check that an exception carries the library's own message."""
import math
import struct
import zlib

import numpy as np
import pytest

from physpix import _native


def rect(world, width, height, **fields):
    """A solid width×height body; keywords are pp_body_def fields."""
    return world.create_body(mask=np.ones((height, width), dtype=np.uint8), **fields)


def raises_from_library(exc_class, words, fn, *args, **kwargs):
    """Call fn, expect exc_class with pp_last_error()'s exact text naming one of words."""
    with pytest.raises(exc_class) as info:
        fn(*args, **kwargs)
    e = info.value
    assert type(e) is exc_class
    assert e.status == exc_class.status
    assert e.library_message == _native.last_error(), "the exception must carry pp_last_error()'s text"
    # The message is the library's, naming the package's call the program made instead of the C function.
    assert e.message == str(e) and e.call and e.message == e.call + e.library_message[len(e.function):], e.message
    assert any(w.lower() in e.message.lower() for w in words), e.message
    return e


def angle_between_deg(a, b):
    """Angle between two 2D directions, degrees in [0, 180]."""
    return abs(math.degrees(math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])))


def wrap_angle(a):
    """An angle folded into (-pi, pi]."""
    return math.atan2(math.sin(a), math.cos(a))


def _chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)


def png_bytes(pixels):
    """A PNG file's bytes: (h, w, 4) uint8 as 8-bit RGBA, (h, w) uint8 as 8-bit gray."""
    pixels = np.ascontiguousarray(pixels, dtype=np.uint8)
    h, w = pixels.shape[:2]
    colour_type = 6 if pixels.ndim == 3 else 0
    raw = b"".join(b"\x00" + pixels[y].tobytes() for y in range(h))  # filter type 0 on every row
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0))
            + _chunk(b"IDAT", zlib.compress(raw)) + _chunk(b"IEND", b""))
