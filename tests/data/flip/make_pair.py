#!/usr/bin/env python3
"""Writes the 32x32 8-bit sRGB PNG pair reference.png / test.png of tests/data/flip/.

Python standard library only (zlib, struct), deterministic. The pair has flat colour regions, hard
edges, a one-pixel line, a gradient and dots, so every part of LDR-FLIP (the three CSF channels,
the edge and point detectors, the remap) sees non-trivial input. See README.md.

Usage: make_pair.py [output folder]   (default: the folder of this script)
"""
import struct
import sys
import zlib
from pathlib import Path

W = H = 32


def pixel(x, y, test):
    """The reference image, or with test=True the test image: the same picture with six changes."""
    # 8x8 checker of a warm red and a mid blue.
    c = (196, 64, 40) if ((x // 8) + (y // 8)) % 2 == 0 else (48, 96, 176)
    # A yellow diagonal band, four pixels wide; one pixel further right in the test image.
    shift = 1 if test else 0
    if 0 <= x - y - shift < 4:
        c = (230, 210, 60)
    # A horizontal grey ramp in rows 24..27; 24 levels darker (clamped at 0) in the test image.
    if 24 <= y < 28:
        v = max(0, 8 * x - (24 if test else 0))
        c = (v, v, v)
    # A one-pixel white line in row 5; only its left half in the test image.
    if y == 5 and (x < 16 or not test):
        c = (250, 250, 250)
    # A green square; bluish green in the test image.
    if 18 <= x < 23 and 2 <= y < 7:
        c = (40, 150, 130) if test else (40, 160, 70)
    # The test image only: two black dots and one white one.
    if test and (x, y) in ((10, 14), (26, 20)):
        c = (0, 0, 0)
    if test and (x, y) == (4, 30):
        c = (255, 255, 255)
    return c


def png(path, pixel):
    rows = b"".join(b"\x00" + bytes(v for x in range(W) for v in pixel(x, y)) for y in range(H))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    # 8-bit RGB, no interlace; an sRGB chunk (rendering intent perceptual) says what the values mean.
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0)) +
            chunk(b"sRGB", b"\x00") + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    Path(path).write_bytes(data)


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent
    png(out / "reference.png", lambda x, y: pixel(x, y, False))
    png(out / "test.png", lambda x, y: pixel(x, y, True))
