"""Worked cases F (section 11, the sketch) and G (section 12, basis images) of
docs/terrain-spec.md, written from that page alone.

Case F: one vertex's sketch term B, in float and double, from a 5 x 4 sketch whose taps reach
past two of its edges. Case G: two 4 x 4 basis images (one normalised, one at weight 0.5),
composed, refined twice per side and sampled by stage 3 at case A's point.

    python3 tests/oracles/sketch_basis_spec.py    prints the literals of
                                                  tests/core/terrain_spec_sketch_basis_cases.h

check_golden.py compares that header's literals with golden() (bit for bit). Standard library
only; float32 by rounding every operation's double result, as terrain_spec.py does.
"""

import math
import struct

import terrain_spec


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def identity(x):
    return x


# ---- Case F: the sketch (section 11) -----------------------------------------------------

SKETCH_W, SKETCH_H = 5, 4
SKETCH_HEIGHT = (-150.0, 850.0)  # terrain.sketch.height
SKETCH_EXTENT = (-1000.0, -2000.0, 1500.0, 3000.0)  # [x0, z0, x1, z1]
SKETCH_CAMERA = (120.25, -310.5)  # (Cx, Cz)
SKETCH_POINT = (-733.5, 1911.75)  # (dx, dz), exact in float


def sketch_grey(i, j):
    """The 16-bit grey of texel (i, j): column i along x, PNG row j along z."""
    return (i * 9973 + j * 21001 + 1234) % 65536


def sketch_texels():
    """Texels: lo + (hi − lo) · (g / 65535) in double, rounded once to float."""
    lo, hi = SKETCH_HEIGHT
    return [f32(lo + (hi - lo) * (sketch_grey(i, j) / 65535.0))
            for j in range(SKETCH_H) for i in range(SKETCH_W)]


def sketch_plan():
    x0, z0, x1, z1 = SKETCH_EXTENT
    cx, cz = SKETCH_CAMERA
    inv_cell_x = SKETCH_W / (x1 - x0)
    inv_cell_z = SKETCH_H / (z1 - z0)
    return {"offset_x": (cx - x0) * inv_cell_x - 0.5, "offset_z": (cz - z0) * inv_cell_z - 0.5,
            "inv_cell_x": inv_cell_x, "inv_cell_z": inv_cell_z}


def bspline_weights(t, R):
    """Section 11's w(t), in this order."""
    u = R(1.0 - t)
    return (R(R(R(u * u) * u) / 6.0),
            R(R(R(R(R(R(t * 3.0) - 6.0) * t) * t) + 4.0) / 6.0),
            R(R(R(R(R(R(3.0 - R(t * 3.0)) * t) + 3.0) * t) + 1.0) / 6.0),
            R(R(R(t * t) * t) / 6.0))


def sketch_point(R):
    """Per vertex, in Real (R rounds to it): the texel coordinate, its cell and B."""
    plan = sketch_plan()
    offset_x, offset_z = R(plan["offset_x"]), R(plan["offset_z"])
    inv_x, inv_z = R(plan["inv_cell_x"]), R(plan["inv_cell_z"])
    max_x, max_z = float(SKETCH_W + 1), float(SKETCH_H + 1)
    dx, dz = SKETCH_POINT

    def clamp(s, top):
        s = -2.0 if s < -2.0 else s  # max(s, −2) = s < −2 ? −2 : s
        return top if top < s else s  # min(s, top)

    s_x = clamp(R(offset_x + R(dx * inv_x)), max_x)
    s_z = clamp(R(offset_z + R(dz * inv_z)), max_z)
    f_x, f_z = float(math.floor(s_x)), float(math.floor(s_z))
    t_x, t_z = R(s_x - f_x), R(s_z - f_z)
    i, j = int(f_x), int(f_z)
    wx, wz = bspline_weights(t_x, R), bspline_weights(t_z, R)
    v = sketch_texels()
    rows = []
    for m in range(4):
        r = min(max(j + m - 1, 0), SKETCH_H - 1)
        c = [min(max(i + k - 1, 0), SKETCH_W - 1) for k in range(4)]
        tap = [v[r * SKETCH_W + ck] for ck in c]
        rows.append(R(R(R(R(wx[0] * tap[0]) + R(wx[1] * tap[1])) + R(wx[2] * tap[2])) +
                      R(wx[3] * tap[3])))
    b = R(R(R(R(wz[0] * rows[0]) + R(wz[1] * rows[1])) + R(wz[2] * rows[2])) + R(wz[3] * rows[3]))
    return {"s_x": s_x, "s_z": s_z, "i": i, "j": j, "t_x": t_x, "t_z": t_z, "b": b}


# ---- Case G: basis images (section 12) -----------------------------------------------------

BASIS_W = 4
BASIS_UPSAMPLE = 2
BASIS_TILE_SIZE = 24000.0
BASIS_WEIGHTS = (1.0, 0.5)


def basis_grey(image, x, y):
    if image == 0:
        return (x * x * 4099 + y * 13001 + 777) % 65536
    return ((x + 2 * y) * 7919 + 4321) % 65536


def basis_image(image):
    """Step 1: g / 65535 in double, v[y · W + x]."""
    return [basis_grey(image, x, y) / 65535.0 for y in range(BASIS_W) for x in range(BASIS_W)]


def normalize(v):
    """Step 3's normalize: sums in row-major order, the population deviation."""
    n2 = float(len(v))
    total = 0.0
    for value in v:
        total = total + value
    mean = total / n2
    squares = 0.0
    for value in v:
        squares = squares + (value - mean) * (value - mean)
    sd = math.sqrt(squares / n2)
    return [(value - mean) / sd for value in v], mean, sd


def compose(images):
    """Step 4: weighted sums over the images in order, then one division."""
    out = []
    for t in range(BASIS_W * BASIS_W):
        weighted, weights = 0.0, 0.0
        for image, weight in zip(images, BASIS_WEIGHTS):
            weighted = weighted + weight * image[t]
            weights = weights + weight
        out.append(weighted / weights)
    return out


def refine(grid, n, k):
    """Step 5: along x first, then along y, periodic taps c − 1 … c + 2; then float."""
    fine = n * k

    def weights(X):
        c = X // k
        return c, bspline_weights(float(X - c * k) / float(k), identity)

    rows = [[0.0] * fine for _ in range(n)]
    for y in range(n):
        for X in range(fine):
            c, w = weights(X)
            total = 0.0
            for m in range(4):
                total = total + w[m] * grid[y * n + (c - 1 + m) % n]
            rows[y][X] = total
    out = []
    for Y in range(fine):
        c, w = weights(Y)
        for X in range(fine):
            total = 0.0
            for m in range(4):
                total = total + w[m] * rows[(c - 1 + m) % n][X]
            out.append(f32(total))
    return out


def basis_case():
    first, mean, sd = normalize(basis_image(0))
    composed = compose([first, basis_image(1)])
    lattice = refine(composed, BASIS_W, BASIS_UPSAMPLE)
    side = BASIS_W * BASIS_UPSAMPLE
    terrain = terrain_spec.Terrain(lattice_size=side, interpolant="linear",
                                   horizontal_scale=BASIS_TILE_SIZE / side)
    camera, (dx, dz, nu) = (0.0, 700.0, 0.0), (1234.5, -2345.25, 5.375)
    plan = terrain_spec.make_plan(terrain, camera)
    heights = {}
    for name, rnd, is_float in (("double", identity, False), ("float", f32, True)):
        params = terrain_spec.Params(plan, terrain, rnd, is_float)
        heights[name] = terrain_spec.fbm_point(params, lattice, dx, dz, nu)
    return mean, sd, composed, lattice, heights


def golden():
    """Every literal of the header: name -> (value or list, kind)."""
    values = {}
    plan = sketch_plan()
    for key in ("offset_x", "offset_z", "inv_cell_x", "inv_cell_z"):
        values["kSketchPlan_" + key] = (plan[key], "double")
    for suffix, rnd, kind in (("Double", identity, "double"), ("Float", f32, "float32")):
        point = sketch_point(rnd)
        for key in ("s_x", "s_z", "t_x", "t_z", "b"):
            values["kSketch%s_%s" % (suffix, key)] = (point[key], kind)
        for key in ("i", "j"):
            values["kSketch%s_%s" % (suffix, key)] = (point[key], "int")
    mean, sd, composed, lattice, heights = basis_case()
    values["kBasisMean"] = (mean, "double")
    values["kBasisDeviation"] = (sd, "double")
    values["kBasisComposed"] = (composed, "double")
    values["kBasisRefined"] = (lattice, "float32")
    for suffix, (height, trace) in (("Double", heights["double"]), ("Float", heights["float"])):
        kind = "double" if suffix == "Double" else "float32"
        values["kBasis%s_height" % suffix] = (height, kind)
        values["kBasis%s_s0" % suffix] = (trace[0].cell.value, kind)
    return values


def cxx_literal(value, kind):
    if kind == "int":
        return "%d" % value
    if kind == "double":
        return repr(value)
    for digits in range(1, 10):
        text = "%.*g" % (digits, value)
        if f32(float(text)) == value:
            return text + "f"
    return repr(value) + "f"


def main():
    types = {"double": "double", "float32": "float", "int": "int"}
    for name, (value, kind) in golden().items():
        if isinstance(value, list):
            items = ", ".join(cxx_literal(v, kind) for v in value)
            print("inline constexpr %s %s[%d] = {%s};" % (types[kind], name, len(value), items))
        else:
            print("inline constexpr %s %s = %s;" % (types[kind], name, cxx_literal(value, kind)))


if __name__ == "__main__":
    main()
