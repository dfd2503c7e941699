#!/usr/bin/env python3
"""Writes the example's textures (plugin/godot/example/*.png) with the standard library alone; run once by hand.

terrain.png: 960 x 200 earth with grass and a canyon 160 px wide, 120 deep, in the middle (transparent there);
bridge.png: 200 x 12 planks; crate.png: 24 x 24 a wooden crate. Colours vary by a fixed hash, not at random,
so the files are the same on every run."""
import struct
import sys
import zlib
from pathlib import Path


def png(path, w, h, pixel):
    rows = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(w)) for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def noise(x, y, k=0):
    n = (x * 374761393 + y * 668265263 + k * 2147483647) & 0xFFFFFFFF
    n = ((n ^ (n >> 13)) * 1274126177) & 0xFFFFFFFF
    return (n >> 24) / 255.0


def shade(rgb, x, y, amount):
    f = 1.0 + amount * (noise(x, y) - 0.5)
    return [max(0, min(255, int(c * f))) for c in rgb] + [255]


def terrain(x, y):
    if 400 <= x < 560 and y < 120:
        return [0, 0, 0, 0]
    top = 0 if not 400 <= x < 560 else 120
    if y - top < 6:
        return shade([70, 150, 60], x, y, 0.3)
    if y > 150 and noise(x // 6, y // 6, 1) > 0.8:
        return shade([110, 110, 115], x, y, 0.3)  # stones
    return shade([130, 90, 55], x, y, 0.25)


def bridge(x, y):
    edge = y in (0, 11) or x % 25 == 0
    return shade([90, 60, 35] if edge else [160, 115, 70], x, y, 0.2)


def crate(x, y):
    frame = x < 3 or y < 3 or x > 20 or y > 20 or abs(x - y) < 2 or abs(x + y - 23) < 2
    return shade([120, 80, 40] if frame else [190, 140, 80], x, y, 0.15)


out = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent / "example")
png(out / "terrain.png", 960, 200, terrain)
png(out / "bridge.png", 200, 12, bridge)
png(out / "crate.png", 24, 24, crate)
