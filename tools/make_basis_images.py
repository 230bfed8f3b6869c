#!/usr/bin/env python3
"""Writes the basis images of §3 Eq. 2 that Relief ships (scenes/basis/craters.png, ridges.png,
dunes.png): 256 x 256 texels, 16-bit grey, from the standard library alone and without random
numbers (positions and lattice values come from an integer hash, everything else is a closed
form), so the files are the same on every machine.

    python3 tools/make_basis_images.py [OUTPUT_DIR]     (default scenes/basis)

Each image TILES by construction (its seam measure, docs/terrain-spec.md section 12, is about
1), because the terrain repeats it over the base domain:

- craters: 48 craters at hashed positions, radii from 6 to 30 texels (small ones more common);
  each a parabolic bowl inside its radius and a raised rim (a Gaussian ring) around it,
  measured with the periodic distance (the shortest way round the torus), summed over a
  mid-grey plain.
- dunes: transverse dune bands, sin^3-sharpened crests of a sinusoid with 5 wavelengths across
  the tile whose phase is warped by two sinusoids along the other axis (integer wave numbers
  throughout, hence periodic), plus a fainter cross set of 11 wavelengths.
- ridges: ridged multifractal-like noise: five octaves of value noise on periodic hash lattices
  of 8, 16, 32, 64 and 128 cells (each cell a whole number of texels), each octave folded as
  (1 - |2 n - 1|)^2 and weighted 0.55^octave.

Each image is scaled to the full grey range by its own minimum and maximum.
"""
import math
import os
import struct
import sys
import zlib

SIZE = 256
MASK64 = (1 << 64) - 1


def hash64(*values):
    """splitmix64 over the values: a deterministic integer hash."""
    h = 0x9E3779B97F4A7C15
    for v in values:
        h = (h ^ (v & MASK64)) & MASK64
        h = (h + 0x9E3779B97F4A7C15) & MASK64
        z = h
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
        h = z ^ (z >> 31)
    return h


def unit(*values):
    """A number in [0, 1) from the hash."""
    return (hash64(*values) >> 11) / float(1 << 53)


def periodic_offset(a, b):
    """b - a the shortest way round the period SIZE."""
    d = (b - a) % SIZE
    return d - SIZE if d > SIZE / 2 else d


def craters():
    img = [[0.0] * SIZE for _ in range(SIZE)]
    for c in range(48):
        cx, cy = unit(1, c, 0) * SIZE, unit(1, c, 1) * SIZE
        radius = 6.0 + 24.0 * unit(1, c, 2) ** 2
        depth = 0.6 + 0.4 * unit(1, c, 3)
        reach = int(radius * 1.8) + 1
        for y in range(int(cy) - reach, int(cy) + reach + 1):
            for x in range(int(cx) - reach, int(cx) + reach + 1):
                d = math.hypot(periodic_offset(cx, x), periodic_offset(cy, y)) / radius
                bowl = -depth * (1.0 - d * d) if d < 1.0 else 0.0
                rim = 0.35 * depth * math.exp(-((d - 1.0) / 0.22) ** 2)
                img[y % SIZE][x % SIZE] += (bowl + rim) * radius / 30.0
    return img


def dunes():
    img = [[0.0] * SIZE for _ in range(SIZE)]
    for y in range(SIZE):
        v = y / SIZE
        warp = 0.35 * math.sin(2 * math.pi * 2 * v) + 0.12 * math.sin(2 * math.pi * 5 * v + 1.0)
        for x in range(SIZE):
            u = x / SIZE
            main = 0.5 + 0.5 * math.sin(2 * math.pi * (5 * u + warp))
            cross = 0.5 + 0.5 * math.sin(2 * math.pi * (11 * v + 3 * u))
            img[y][x] = main ** 3 + 0.15 * cross
    return img


def value_noise(x, y, cells, octave):
    """Periodic value noise: cells x cells hashed values, smoothstep-interpolated."""
    step = SIZE / cells
    fx, fy = x / step, y / step
    i, j = int(fx), int(fy)
    tx, ty = fx - i, fy - j
    sx, sy = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)

    def at(a, b):
        return unit(3, octave, a % cells, b % cells)

    top = at(i, j) + (at(i + 1, j) - at(i, j)) * sx
    bottom = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx
    return top + (bottom - top) * sy


def ridges():
    img = [[0.0] * SIZE for _ in range(SIZE)]
    for y in range(SIZE):
        for x in range(SIZE):
            total = 0.0
            for octave, cells in enumerate((8, 16, 32, 64, 128)):
                n = value_noise(x, y, cells, octave)
                total += 0.55 ** octave * (1.0 - abs(2.0 * n - 1.0)) ** 2
            img[y][x] = total
    return img


def write_png16(path, img):
    lo = min(min(row) for row in img)
    hi = max(max(row) for row in img)
    raw = bytearray()
    for row in img:
        raw.append(0)  # filter: none
        for v in row:
            raw += struct.pack(">H", round((v - lo) / (hi - lo) * 65535))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", SIZE, SIZE, 16, 0, 0, 0, 0)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(raw), 9))
           + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("scenes", "basis")
    os.makedirs(out, exist_ok=True)
    for name, make in (("craters", craters), ("dunes", dunes), ("ridges", ridges)):
        write_png16(os.path.join(out, name + ".png"), make())


if __name__ == "__main__":
    main()
