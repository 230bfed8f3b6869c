#!/usr/bin/env python3
"""A real elevation model rendered as the terrain, in every backend (issue 25).

    real_dem_test.py RELIEF_BINARY DEM_NPZ [--gl]          the test
    real_dem_test.py --write-scene DIR DEM_NPZ              the DEM as DIR/jacksboro.pfm and
                                                            DIR/jacksboro.json, for the docs

The DEM is matplotlib's sample of the Jacksboro fault, Tennessee (Debian's
python-matplotlib-data: mpl-data/sample_data/jacksboro_fault_dem.npz): 344 x 403 USGS
elevations in metres on a 3-arc-second grid, row 0 at its north edge. Its geographic grid is
placed in local metres as matplotlib's own hill-shading example does (111,200 m a degree of
latitude, times the cosine of the middle latitude along a parallel), centred on the origin:
north up (-z), texel centres half a cell inside the extent (docs/terrain-spec.md section 11).

Each backend (reference, reference-double, simd and, with --gl, gl) renders it straight down
with `--height`; every pixel's world position is rebuilt from the camera's ray through the
pixel centre and the height there (the camera's conventions, core/camera.h), and checked
against the DEM itself, independently of Relief:

- hull: the field is the uniform cubic B-spline of the samples (interpolating: false), whose
  weights are non-negative, so at any point it lies within the extremes of the 4 x 4 samples
  around it; a pixel interpolates the vertices of its triangle, all within a sample of it
  (the grid is finer than the pixels, a pixel about one sample), so its height lies within
  the extremes of the 6 x 6 samples around it. Every pixel, every backend.
- placement: the B-spline itself, transcribed here from docs/terrain-spec.md section 11, at
  each pixel's point: the mean difference from the rendered height (the grid's linear
  interpolation between its vertices) must be under a third of the mean difference from the
  same DEM moved by a quarter of a sample (measured on AMD Zen 4: 0.50 m against 2.98 m), and
  the hull check against the DEM turned upside down must fail on a fifth of the pixels or more:
  together they see where the field lies, and that its rows run north to south.
- the simd backend's PNG is the reference's byte for byte.

Then the same DEM drawn by GeoMipMapping (terrain.heightfield.geomipmap) in each backend:
every pixel within the extremes of its tile's samples (a tile's triangles interpolate its own
lattice points, each the B-spline at a texel centre), the placement check against the DEM
moved half a sample (the mesh is linear between texel centres: measured 1.02 m from the
B-spline against 6 m), the simd PNG the reference's.

Python 3's standard library only (the .npz is a zip of .npy arrays, read here).
"""
import ast
import io
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import zipfile

METRES_PER_DEGREE = 111200.0  # matplotlib's hill-shading example
VIEW = {"width": 320, "height": 288}
ALTITUDE = 21000.0  # above the origin: about one sample a pixel
# GeoMipMapping: tiles of 16 samples, levels whose error seen from the camera is at most 0.01
# px (de Boer's metric takes vertical error at the distance; looking straight down that is
# 0.84 m at 21 km, so a coarse level's plane stays within a fraction of the samples' spread).
GEOMIPMAP = {"tile_cells": 16, "pixel_error": 0.01}


def read_npy(data):
    """One .npy array (version 1 or 2, C order) as (shape, flat list)."""
    if data[:6] != b"\x93NUMPY":
        raise ValueError("not an .npy array")
    major = data[6]
    if major == 1:
        (length,), start = struct.unpack("<H", data[8:10]), 10
    else:
        (length,), start = struct.unpack("<I", data[8:12]), 12
    header = ast.literal_eval(data[start:start + length].decode("latin-1"))  # a dict literal
    if header["fortran_order"]:
        raise ValueError("Fortran-order array")
    codes = {"<i2": "h", "<f8": "d", "<f4": "f", "<i4": "i"}
    code = codes[header["descr"]]
    count = 1
    for n in header["shape"]:
        count *= n
    body = data[start + length:]
    values = struct.unpack("<%d%s" % (count, code), body[:count * struct.calcsize(code)])
    return header["shape"], list(values)


def read_dem(path):
    with zipfile.ZipFile(path) as archive:
        arrays = {name[:-4]: read_npy(archive.read(name)) for name in archive.namelist()}
    (rows, columns), elevation = arrays["elevation"]
    scalar = lambda key: arrays[key][1][0]
    north, south = scalar("ymin"), scalar("ymax")  # row 0 is the north edge (36.73 N)
    west, east = scalar("xmin"), scalar("xmax")
    middle = math.radians((north + south) / 2)
    width_m = (east - west) * METRES_PER_DEGREE * math.cos(middle)
    depth_m = (north - south) * METRES_PER_DEGREE
    extent = [-width_m / 2, -depth_m / 2, width_m / 2, depth_m / 2]
    heights = [[float(elevation[r * columns + c]) for c in range(columns)] for r in range(rows)]
    return heights, extent


def write_pfm(path, heights):
    rows, columns = len(heights), len(heights[0])
    out = io.BytesIO()
    out.write(b"Pf\n%d %d\n-1.0\n" % (columns, rows))
    for row in reversed(heights):  # PFM rows bottom (south, z1) to top (north, z0)
        out.write(struct.pack("<%df" % columns, *row))
    with open(path, "wb") as f:
        f.write(out.getvalue())


def scene_for(pfm_name, extent, low, high, geomipmap=None):
    scene = {
        "camera": {"position": [0.0, ALTITUDE, 0.0], "yaw_deg": 0.0, "pitch_deg": -90.0,
                   "fov_y_deg": 60.0, "near": 1.0, "far": 60000.0},
        "viewport": VIEW,
        "grid": {"width": 448, "height": 448},
        "terrain": {"base_height": 0.0, "water_level": low - 100.0,
                    "heightfield": {"file": pfm_name, "extent": extent, "height": [0.0, 1.0]}},
    }
    if geomipmap is not None:
        scene["terrain"]["heightfield"]["geomipmap"] = geomipmap
    return scene


def read_float_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    width, height = map(int, parts[1].split())
    scale = float(parts[2])
    endian = "<" if scale < 0 else ">"
    values = struct.unpack(endian + "%df" % (width * height), parts[3][:4 * width * height])
    return width, height, values  # rows bottom (window row 0) to top


def pixel_points(heights_image):
    """Each covered pixel's world (x, z, height) from its ray (core/camera.h, pitch -90)."""
    width, height, values = heights_image
    tan_y = math.tan(math.radians(30.0))
    tan_x = tan_y * width / height
    # pitch -90, yaw 0: forward (0, -1, 0), right (1, 0, 0), up = right x forward = (0, 0, -1)
    points = []
    for py in range(height):
        for px in range(width):
            h = values[py * width + px]
            if not math.isfinite(h):
                continue
            ndc_x = (px + 0.5) / width * 2 - 1
            ndc_y = (py + 0.5) / height * 2 - 1
            dx, dy, dz = ndc_x * tan_x, -1.0, -ndc_y * tan_y
            t = (h - ALTITUDE) / dy
            points.append((dx * t, dz * t, h))
    return points


def hull_failures(points, heights, extent, flip=False):
    rows, columns = len(heights), len(heights[0])
    cell_x = (extent[2] - extent[0]) / columns
    cell_z = (extent[3] - extent[1]) / rows
    failures = 0
    for x, z, h in points:
        sx = (x - extent[0]) / cell_x - 0.5
        sz = (z - extent[1]) / cell_z - 0.5
        i, j = math.floor(sx), math.floor(sz)
        low, high = math.inf, -math.inf
        for m in range(j - 2, j + 4):
            r = min(max(m, 0), rows - 1)
            if flip:
                r = rows - 1 - r
            row = heights[r]
            for k in range(i - 2, i + 4):
                v = row[min(max(k, 0), columns - 1)]
                low, high = min(low, v), max(high, v)
        # The rendered height is float vertex heights interpolated in float: a few ulps of
        # ~1000 m (6e-5 m each); 1e-5 relative (1 cm) leaves room for GL's interpolation.
        slack = 1e-5 * max(1.0, abs(h))
        if not (low - slack <= h <= high + slack):
            failures += 1
    return failures


def mesh_hull_failures(points, heights, extent, tile):
    """GeoMipMapping: a pixel interpolates its triangle's vertices, lattice points of the tile
    that holds it (every vertex of a tile's triangles is one of its (T + 1)^2 points, at texel
    centres), each the B-spline there, within the extremes of the 3 x 3 samples around it. So
    a pixel's height lies within the extremes of the samples of its tile widened by one sample;
    taken here over the tiles two either side of the pixel's (blocks of T samples)."""
    rows, columns = len(heights), len(heights[0])
    cell_x = (extent[2] - extent[0]) / columns
    cell_z = (extent[3] - extent[1]) / rows
    blocks_x, blocks_z = (columns + tile - 1) // tile, (rows + tile - 1) // tile
    block = {}
    for bz in range(blocks_z):
        for bx in range(blocks_x):
            values = [heights[r][c] for r in range(bz * tile, min(rows, (bz + 1) * tile))
                      for c in range(bx * tile, min(columns, (bx + 1) * tile))]
            block[(bx, bz)] = (min(values), max(values))
    failures = 0
    for x, z, h in points:
        tx = math.floor(((x - extent[0]) / cell_x - 0.5) / tile)
        tz = math.floor(((z - extent[1]) / cell_z - 0.5) / tile)
        low, high = math.inf, -math.inf
        for bz in range(tz - 2, tz + 3):
            for bx in range(tx - 2, tx + 3):
                b = block[(min(max(bx, 0), blocks_x - 1), min(max(bz, 0), blocks_z - 1))]
                low, high = min(low, b[0]), max(high, b[1])
        slack = 1e-5 * max(1.0, abs(h))
        if not (low - slack <= h <= high + slack):
            failures += 1
    return failures


def bspline_weights(t):
    u = 1 - t
    return [u * u * u / 6, ((3 * t - 6) * t * t + 4) / 6, (((3 - 3 * t) * t + 3) * t + 1) / 6,
            t * t * t / 6]


def mean_bspline_difference(points, heights, extent, shift=0.0):
    """Mean |rendered height - the samples' cubic B-spline| at the pixels' points, the DEM
    moved by `shift` samples east."""
    rows, columns = len(heights), len(heights[0])
    cell_x = (extent[2] - extent[0]) / columns
    cell_z = (extent[3] - extent[1]) / rows
    total = 0.0
    for x, z, h in points:
        sx = (x - extent[0]) / cell_x - 0.5 - shift
        sz = (z - extent[1]) / cell_z - 0.5
        i, j = math.floor(sx), math.floor(sz)
        wx, wz = bspline_weights(sx - i), bspline_weights(sz - j)
        value = 0.0
        for m in range(4):
            row = heights[min(max(j + m - 1, 0), rows - 1)]
            value += wz[m] * sum(wx[k] * row[min(max(i + k - 1, 0), columns - 1)]
                                 for k in range(4))
        total += abs(h - value)
    return total / len(points)


def render_points(relief, scene, backend, work, name):
    """`scene` rendered straight down by `backend`: its PNG's bytes, each covered pixel's world
    point and the share of pixels covered."""
    png = os.path.join(work, name + ".png")
    heights_pfm = os.path.join(work, name + "-height.pfm")
    run([relief, "render", scene, "--backend", backend, "--threads", "2", "-o", png,
         "--height", heights_pfm])
    with open(png, "rb") as f:
        data = f.read()
    points = pixel_points(read_float_pfm(heights_pfm))
    return data, points, len(points) / (VIEW["width"] * VIEW["height"])


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit("FAILED (exit %d): %s\n%s%s" % (result.returncode, " ".join(cmd),
                                                         result.stdout, result.stderr))


def write_scene(directory, npz):
    heights, extent = read_dem(npz)
    write_pfm(os.path.join(directory, "jacksboro.pfm"), heights)
    flat = [v for row in heights for v in row]
    scene = scene_for("jacksboro.pfm", extent, min(flat), max(flat))
    with open(os.path.join(directory, "jacksboro.json"), "w") as f:
        json.dump(scene, f, indent=2)
    mesh = scene_for("jacksboro.pfm", extent, min(flat), max(flat), GEOMIPMAP)
    with open(os.path.join(directory, "jacksboro-geomipmap.json"), "w") as f:
        json.dump(mesh, f, indent=2)
    return heights, extent


def main(argv):
    if len(argv) == 4 and argv[1] == "--write-scene":
        write_scene(argv[2], argv[3])
        return 0
    if len(argv) not in (3, 4) or (len(argv) == 4 and argv[3] != "--gl"):
        print(__doc__, file=sys.stderr)
        return 2
    relief, npz = argv[1], argv[2]
    backends = ["reference", "reference-double", "simd"] + (["gl"] if len(argv) == 4 else [])
    if not os.path.isfile(npz):
        raise SystemExit("FAILED: the DEM %s is missing (Debian's python-matplotlib-data)" % npz)
    failed = False
    with tempfile.TemporaryDirectory(prefix="relief-dem-") as work:
        heights, extent = write_scene(work, npz)
        scene = os.path.join(work, "jacksboro.json")
        pngs = {}
        for backend in backends:
            pngs[backend], points, covered = render_points(relief, scene, backend, work, backend)
            outside = hull_failures(points, heights, extent)
            print("%s: %d pixels covered (%.1f %%), %d outside the 6 x 6 samples' extremes" %
                  (backend, len(points), 100 * covered, outside))
            here = mean_bspline_difference(points, heights, extent)
            moved = mean_bspline_difference(points, heights, extent, shift=0.25)
            flipped = hull_failures(points, heights, extent, flip=True)
            print("  mean |height - B-spline|: %.3f m; the DEM moved a quarter sample: %.3f m; "
                  "upside down: %d pixels outside its extremes" % (here, moved, flipped))
            if covered < 0.999 or outside != 0 or not here < moved / 3:
                failed = True
            if flipped < 0.2 * len(points):
                print("  FAILED: the hull check cannot tell north from south")
                failed = True
        if pngs["simd"] != pngs["reference"]:
            print("FAILED: the simd backend's PNG differs from the reference's")
            failed = True
        # The same DEM drawn by GeoMipMapping (docs/heightfields.md), in every backend.
        mesh_scene = os.path.join(work, "jacksboro-geomipmap.json")
        for backend in backends:
            pngs[backend + " geomipmap"], points, covered = render_points(
                relief, mesh_scene, backend, work, backend + "-geomipmap")
            outside = mesh_hull_failures(points, heights, extent, GEOMIPMAP["tile_cells"])
            # The mesh is linear between texel centres (1.02 m from the B-spline on average where
            # the grid's finer vertices give 0.50): judged against the DEM moved half a sample.
            here = mean_bspline_difference(points, heights, extent)
            moved = mean_bspline_difference(points, heights, extent, shift=0.5)
            print("%s, GeoMipMapping: %d pixels covered (%.1f %%), %d outside their tiles' "
                  "samples' extremes; mean |height - B-spline| %.3f m, the DEM moved half a "
                  "sample %.3f m" % (backend, len(points), 100 * covered, outside, here, moved))
            if covered < 0.999 or outside != 0 or not here < moved / 3:
                failed = True
        if pngs["simd geomipmap"] != pngs["reference geomipmap"]:
            print("FAILED: the simd backend's GeoMipMap PNG differs from the reference's")
            failed = True
    print("FAILED" if failed else "passed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
