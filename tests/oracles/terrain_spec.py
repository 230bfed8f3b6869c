"""Stage 3's terrain function of docs/terrain-spec.md, written from that page alone.

This is the "independent Python implementation" the page cites: float64 natively, float32 by
rounding the result of every + - x / and sqrt to binary32. For binary32 operands that is exactly
the binary32 operation (the double result has more than 2 * 24 + 2 bits, so rounding it again
cannot differ from rounding the exact result once). Section numbers below are the page's.
Standard library only; pow and hypot are the C library's, as section 2 requires.
"""

import ctypes
import ctypes.util
import math
from dataclasses import dataclass, field

import noise_lattice

VELTKAMP_DOUBLE = 134217729.0  # 2^27 + 1 (section 2, split; section 4, split_R for double)
VELTKAMP_FLOAT = 4097.0  # 2^12 + 1 (section 4, split_R for float)
GUARD_SQ = 0.5 * 0.5  # section 2: limits::kRoughnessGuard squared
MIN_ROTATION_SQ = 1e-12  # section 2: limits::kMinRotationLengthSq
MAX_OCTAVE_INDEX = 23  # section 4, m(v): "23 otherwise"


def _c_library_hypot():
    """Section 2 takes hypot from the C library; CPython's math.hypot is its own algorithm
    (correctly rounded, which glibc's is not always), so call libm when it can be loaded."""
    for name in ("libm.so.6", ctypes.util.find_library("m")):
        if not name:
            continue
        try:
            function = ctypes.CDLL(name).hypot
        except (OSError, AttributeError):
            continue
        function.restype = ctypes.c_double
        function.argtypes = (ctypes.c_double, ctypes.c_double)
        return function
    return math.hypot


c_hypot = _c_library_hypot()
# CPython's math.pow calls the C library's pow for finite arguments (section 2: "C library pow").
c_pow = math.pow


@dataclass
class Terrain:
    """The scene values of "Notation"; defaults are those of "Worked numbers" (the default
    terrain: seed 1, P = 256, quintic, r = 2, H = 0.85, k0 = 0, k1 = 14, s = 3000, base 100,
    A = 360, warp off). The warp constants default to Figure 3's, which the page does not print:
    they are scenes/lava.json's c1, c2, c3 (case D, "warp (lava)")."""
    seed: int = 1
    lattice_size: int = 256
    interpolant: str = "quintic"
    r: float = 2.0
    H: float = 0.85
    first_octave: int = 0
    last_octave: int = 14
    horizontal_scale: float = 3000.0
    base_height: float = 100.0
    amplitude: float = 360.0
    warp: bool = False
    c1: tuple = (0.35, 0.16)
    c2: tuple = (-0.07, 0.13)
    c3: tuple = (0.11, 0.17)
    r0: tuple = (1.0, 0.0)
    t0: tuple = (0.0, 0.0)


# ---- Section 2: the plan, per frame, in double -------------------------------------------

def pmod(v, m):
    q = math.fmod(v, m)  # exact
    if q < 0:
        q = q + m
    return q - m if q >= m else q


def veltkamp_split(a, constant, rnd):
    t = rnd(constant * a)
    hi = rnd(t - rnd(t - a))
    return hi, rnd(a - hi)


def two_product_error(a, b, p):
    """Dekker: a*b - p exactly, for p = fl(a*b) (section 2)."""
    a_hi, a_lo = veltkamp_split(a, VELTKAMP_DOUBLE, float)
    b_hi, b_lo = veltkamp_split(b, VELTKAMP_DOUBLE, float)
    return (((a_hi * b_hi - p) + a_hi * b_lo) + a_lo * b_hi) + a_lo * b_lo


def product_mod(a, b, c, period):
    """(a*b + c) mod P in [0, P), with the product's rounding error kept (section 2)."""
    p = a * b
    e = two_product_error(a, b, p)
    return pmod((pmod(p, period) + pmod(e, period)) + pmod(c, period), period)


@dataclass
class Plan:
    frequency: list = field(default_factory=list)  # f_n = r^k by repeated products
    amplitude: list = field(default_factory=list)  # a_n = pow(r, -k H)
    scale: list = field(default_factory=list)  # g_n = f_n / s
    omega_x: list = field(default_factory=list)
    omega_z: list = field(default_factory=list)
    offset_x: list = field(default_factory=list)
    offset_z: list = field(default_factory=list)
    periodic: bool = False
    world_period: float = 0.0
    r0: tuple = (1.0, 0.0)
    roughness0: float = 1.0
    inv_scale: float = 1.0
    relative_base_height: float = 0.0


def make_plan(terrain, camera):
    """make_octave_table and make_terrain_plan of section 2, for camera = (Cx, Cy, Cz)."""
    P, s, r = terrain.lattice_size, terrain.horizontal_scale, terrain.r
    plan = Plan()
    for n in range(terrain.last_octave - terrain.first_octave + 1):
        k = terrain.first_octave + n
        f = 1.0
        for _ in range(k):
            f = f * r
        plan.frequency.append(f)
        plan.amplitude.append(c_pow(r, float(-k) * terrain.H))
        plan.scale.append(f / s)
        plan.omega_x.append(noise_lattice.octave_offset(terrain.seed, k, 0, P))
        plan.omega_z.append(noise_lattice.octave_offset(terrain.seed, k, 1, P))
    plan.periodic = all(f == math.floor(f) and f < 2.0 ** 53 for f in plan.frequency)
    plan.world_period = P * s
    cx, cy, cz = camera
    if plan.periodic:
        cx, cz = pmod(cx, plan.world_period), pmod(cz, plan.world_period)
    lam_x, lam_z = cx / s, cz / s
    for n, f in enumerate(plan.frequency):
        plan.offset_x.append(product_mod(f, lam_x, plan.omega_x[n], P))
        plan.offset_z.append(product_mod(f, lam_z, plan.omega_z[n], P))
    length = c_hypot(terrain.r0[0], terrain.r0[1])
    plan.r0 = (terrain.r0[0] / length, terrain.r0[1] / length)
    plan.roughness0 = c_pow(r, terrain.H)
    plan.inv_scale = 1.0 / s
    plan.relative_base_height = terrain.base_height - cy
    return plan


# ---- Section 8: height bounds (world heights, double) ------------------------------------

def height_bounds(terrain, lattice_min, lattice_max):
    total = 0.0
    for k in range(terrain.first_octave, terrain.last_octave + 1):
        total = total + c_pow(terrain.r, float(-k) * terrain.H)
    fbm_min = total * min(0.0, lattice_min)
    fbm_max = total * max(0.0, lattice_max)
    slack = 1e-5 * max(abs(fbm_min), abs(fbm_max))
    return (terrain.base_height + terrain.amplitude * (fbm_min - slack),
            terrain.base_height + terrain.amplitude * (fbm_max + slack))


# ---- Section 3: the plan rounded once to the stage's type --------------------------------

class Params:
    """FbmParams<Real>; `rnd` is identity for double and the binary32 rounding for float."""

    def __init__(self, plan, terrain, rnd, is_float):
        self.rnd, self.is_float = rnd, is_float
        self.count = len(plan.frequency)
        self.interpolant = terrain.interpolant
        self.frequency = [rnd(f) for f in plan.frequency]
        self.amplitude = [rnd(a) for a in plan.amplitude]
        self.offset_x = [rnd(o) for o in plan.offset_x]
        self.offset_z = [rnd(o) for o in plan.offset_z]
        self.scale_pieces = [self._pieces(g) for g in plan.scale]  # per octave: [(piece, hi, lo)]
        self.period = float(terrain.lattice_size)
        self.inv_period = rnd(1.0 / self.period)
        self.inv_scale = rnd(plan.inv_scale)
        self.relative_base_height = rnd(plan.relative_base_height)
        self.height_scale = rnd(terrain.amplitude)
        self.c1 = tuple(rnd(v) for v in terrain.c1)
        self.c2 = tuple(rnd(v) for v in terrain.c2)
        self.c3 = tuple(rnd(v) for v in terrain.c3)
        self.r0 = tuple(rnd(v) for v in plan.r0)
        self.t0 = tuple(rnd(v) for v in terrain.t0)
        self.roughness0 = rnd(plan.roughness0)
        self.guard_sq = GUARD_SQ
        self.min_rotation_sq = rnd(MIN_ROTATION_SQ)
        self.lacunarity = rnd(terrain.r)
        self.warp = terrain.warp
        self.plan_scale = plan.scale

    def split(self, a):
        return veltkamp_split(a, VELTKAMP_FLOAT if self.is_float else VELTKAMP_DOUBLE, self.rnd)

    def _pieces(self, g):
        """scale_piece: three floats that hold the double g exactly, or g itself in double."""
        if self.is_float:
            pieces, rest = [], g
            for _ in range(3):
                piece = self.rnd(rest)
                pieces.append(piece)
                rest = rest - piece  # double, exact
        else:
            pieces = [g]
        return [(piece,) + self.split(piece) for piece in pieces]


# ---- Section 4: the per-octave coordinate -------------------------------------------------

def finest_octave(nu):
    """m(v) of section 4: the finest octave a vertex with this nu sums."""
    if nu <= 1:
        return 0
    if nu < MAX_OCTAVE_INDEX + 1:
        return math.ceil(nu) - 1
    return MAX_OCTAVE_INDEX


def choose_exact_forms(params, dx, dz, nu):
    """The choice of section 4 for a frame of one valid vertex, decided in double."""
    extent, finest = max(abs(dx), abs(dz)), finest_octave(nu)
    return [1 if params.plan_scale[n] * (extent if finest >= n else 0.0) > params.period else 0
            for n in range(params.count)]


def wrap(params, v):
    """wrap(v) = v − period · floor(v · inv_period) (sections 4 and 5)."""
    R = params.rnd
    return R(v - R(params.period * float(math.floor(R(v * params.inv_period)))))


def sum_error(R, a, b, s):
    """Knuth's two-sum error: a + b − s exactly for s = fl(a + b)."""
    b_v = R(s - a)
    a_v = R(s - b_v)
    return R(R(a - a_v) + R(b - b_v))


def exact_coordinate(params, n, d):
    """The exact form of section 4: g_n · d mod P with one rounding in all."""
    R = params.rnd
    d_hi, d_lo = params.split(d)
    total_sum, carry = 0.0, 0.0

    def add(term):
        nonlocal total_sum, carry
        w = wrap(params, term)
        total = R(total_sum + w)
        carry = R(carry + sum_error(R, total_sum, w, total))
        total_sum = wrap(params, total)

    for piece, hi, lo in reversed(params.scale_pieces[n]):  # the smallest piece first
        prod = R(d * piece)
        err = R(R(R(R(R(d_hi * hi) - prod) + R(d_hi * lo)) + R(d_lo * hi)) + R(d_lo * lo))
        add(err)  # error before product
        add(prod)
    return wrap(params, R(total_sum + carry))


def coordinate_term(params, n, d, exact):
    """G = g_n · d in the form chosen for octave n (section 4)."""
    if exact:
        return exact_coordinate(params, n, d)
    return params.rnd(params.frequency[n] * params.rnd(d * params.inv_scale))


# ---- Section 5: the interpolated lattice S -------------------------------------------------

def fade(params, t):
    R = params.rnd
    if params.interpolant == "linear":
        return t
    if params.interpolant == "cubic":
        return R(R(t * t) * R(3.0 - R(2.0 * t)))
    return R(R(R(t * t) * t) * R(R(t * R(R(t * 6.0) - 15.0)) + 10.0))


@dataclass
class Cell:
    i0: int
    j0: int
    i1: int
    j1: int
    t_x: float
    t_z: float
    fade_x: float
    fade_z: float
    corners: tuple  # L(i0, j0), L(i1, j0), L(i0, j1), L(i1, j1)
    value: float  # S(p)


def sample_lattice(params, lattice, p_x, p_z):
    """locate_cell and sample_lattice: lerps along x first, then along z."""
    R, size = params.rnd, int(params.period)
    mask = size - 1
    w_x, w_z = wrap(params, p_x), wrap(params, p_z)
    f_x, f_z = float(math.floor(w_x)), float(math.floor(w_z))
    i0, j0 = int(f_x) & mask, int(f_z) & mask
    i1, j1 = (i0 + 1) & mask, (j0 + 1) & mask
    t_x, t_z = R(w_x - f_x), R(w_z - f_z)
    fade_x, fade_z = fade(params, t_x), fade(params, t_z)
    v00, v10 = lattice[j0 * size + i0], lattice[j0 * size + i1]
    v01, v11 = lattice[j1 * size + i0], lattice[j1 * size + i1]
    bottom = R(v00 + R(fade_x * R(v10 - v00)))
    top = R(v01 + R(fade_x * R(v11 - v01)))
    value = R(bottom + R(fade_z * R(top - bottom)))
    return Cell(i0, j0, i1, j1, t_x, t_z, fade_x, fade_z, (v00, v10, v01, v11), value)


# ---- Sections 6 and 7: the sum, the LOD weights and the warp -------------------------------

@dataclass
class OctaveTrace:
    """One row of a worked table: what octave n sampled and the partial sum after it."""
    exact: int
    offset_x: float
    offset_z: float
    g_x: float
    g_z: float
    w_x: float
    w_z: float
    p_x: float
    p_z: float
    cell: Cell
    partial_sum: float  # h_n
    height: float  # relative_base_height + height_scale · h_n


def warp_update(params, h, rot, displacement):
    """Section 7, in its order; returns the new rotation and W for the next octave."""
    R = params.rnd
    rough = R(params.roughness0 - h)
    inv_rough = R(rough / R(R(rough * rough) + params.guard_sq))
    v_x = R(R(R(params.c1[0] * rough) + params.c2[0]) + rot[0])
    v_z = R(R(R(params.c1[1] * rough) + params.c2[1]) + rot[1])
    len_sq = R(R(v_x * v_x) + R(v_z * v_z))
    if len_sq > params.min_rotation_sq:
        inv_len = R(1.0 / R(math.sqrt(len_sq)))
        rot = (R(v_x * inv_len), R(v_z * inv_len))
    q = R(h * inv_rough)
    w_x, w_z = displacement
    next_x = R(R(R(rot[0] * w_x) - R(rot[1] * w_z)) + R(params.c3[0] * q))
    next_z = R(R(R(rot[1] * w_x) + R(rot[0] * w_z)) + R(params.c3[1] * q))
    return rot, (R(params.lacunarity * next_x), R(params.lacunarity * next_z))


def fbm_point(params, lattice, dx, dz, nu):
    """fbm_height of one point (a frame of this one vertex): (height − Cy, per-octave trace).

    dx, dz and nu must already be of the stage's type (exact in float for the worked cases).
    """
    R = params.rnd
    exact = choose_exact_forms(params, dx, dz, nu)
    whole = float(math.floor(nu))
    full = int(whole) if whole < float(params.count) else params.count
    frac = R(nu - whole)
    h = 0.0
    displacement, rot = params.t0, params.r0
    trace = []
    for n in range(params.count):
        weight = 1.0 if n < full else frac
        if n > full or weight == 0:
            break
        g_x = coordinate_term(params, n, dx, exact[n])
        g_z = coordinate_term(params, n, dz, exact[n])
        p_x = R(R(params.offset_x[n] + g_x) + displacement[0])
        p_z = R(R(params.offset_z[n] + g_z) + displacement[1])
        cell = sample_lattice(params, lattice, p_x, p_z)
        h = R(h + R(R(weight * params.amplitude[n]) * cell.value))
        height = R(params.relative_base_height + R(params.height_scale * h))
        trace.append(OctaveTrace(exact[n], params.offset_x[n], params.offset_z[n], g_x, g_z,
                                 displacement[0], displacement[1], p_x, p_z, cell, h, height))
        if params.warp and n < full and n + 1 < params.count:
            rot, displacement = warp_update(params, h, rot, displacement)
    return R(params.relative_base_height + R(params.height_scale * h)), trace
