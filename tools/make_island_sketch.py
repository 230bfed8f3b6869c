#!/usr/bin/env python3
"""Writes scenes/sketches/island.png, the height sketch of the `island` preset (§3's
low-frequency base): 128 x 128 texels, 16-bit grey, deterministic (no random numbers, only
closed forms), from the standard library alone.

    python3 tools/make_island_sketch.py [OUTPUT]

The island: a radial falloff (a smooth bump of radius 0.62 of the half-side around a centre
slightly off the middle, squashed along z) plus four Gaussian hills (a main peak, a ridge
shoulder, a southern hill, a small islet offshore), divided by 1.05 (the highest point stays
below white, so nothing is clipped flat). The falloff leaves the sea floor flat beyond the
coast. Grey 0 is the deep sea floor, 65535 the summit; the
preset maps them to world heights with terrain.sketch.height.
"""
import math
import struct
import sys
import zlib

SIZE = 128

# (centre x, centre z, radius, height): in units of the half-side, z down the image.
HILLS = [
    (0.10, -0.05, 0.28, 0.55),   # the main peak, a little north-east of the middle
    (-0.22, 0.10, 0.22, 0.30),   # a shoulder to the west
    (0.05, 0.38, 0.18, 0.22),    # a southern hill
    (0.62, -0.55, 0.10, 0.30),   # an islet offshore, north-east
]


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def height(u, v):
    """Normalised height in [0, 1] at (u, v) in [-1, 1]^2."""
    r = math.hypot((u + 0.05) / 0.62, (v - 0.02) / 0.52)
    land = 0.45 * (1.0 - smoothstep(0.55, 1.15, r))
    for cx, cz, radius, amount in HILLS:
        d2 = ((u - cx) ** 2 + (v - cz) ** 2) / (radius * radius)
        land += amount * math.exp(-d2)
    return min(land / 1.05, 1.0)  # the highest point, 1.03, stays below white: no plateau


def png16(width, height_px, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    raw = b"".join(b"\x00" + struct.pack(">%dH" % width, *row) for row in rows)
    ihdr = struct.pack(">IIBBBBB", width, height_px, 16, 0, 0, 0, 0)  # 16-bit grey
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) +
            chunk(b"IEND", b""))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/sketches/island.png"
    rows = []
    for j in range(SIZE):
        v = (j + 0.5) / SIZE * 2.0 - 1.0
        rows.append([round(65535 * height((i + 0.5) / SIZE * 2.0 - 1.0, v)) for i in range(SIZE)])
    with open(out, "wb") as f:
        f.write(png16(SIZE, SIZE, rows))


if __name__ == "__main__":
    main()
