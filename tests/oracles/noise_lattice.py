"""The noise lattice of docs/noise-lattice.md, written from that page alone.

This is the "independent transcription" the page cites for its golden hash: it is kept here so
that anyone can re-derive the lattice's test vectors (tests/core/lattice_test.cc) without the
C++.
Python integers are unbounded, so every 64-bit step is masked explicitly; Python floats are
IEEE-754 binary64 with round-to-nearest and no fused multiply-add, which is what the page asks
for. Standard library only.
"""

import math
import struct

MASK64 = (1 << 64) - 1

# "The hash": g, the golden-ratio increment of SplitMix64.
GOLDEN_GAMMA = 0x9E3779B97F4A7C15

# "Streams: 0 = lattice values, 1 = per-octave offsets."
STREAM_LATTICE = 0
STREAM_OCTAVE_OFFSET = 1

# "log2_det": the series coefficients c[k] = 2 / ((2k + 1) ln 2), as the page prints the
# doubles (float() of a decimal string is correctly rounded, so these are those doubles).
LOG2_SERIES = tuple(float(text) for text in (
    "2.8853900817779268", "0.9617966939259757", "0.5770780163555853",
    "0.41219858311113244", "0.3205988979753252", "0.2623081892525388",
    "0.2219530832136867", "0.19235933878519512", "0.16972882833987804",
    "0.15186263588304877", "0.1373995277037108", "0.12545174268599682"))
SQRT2 = 1.4142135623730951
LN2 = 0.69314718055994531

# "Lattice values": at most 64 attempts of the polar method per cell.
MAX_POLAR_ATTEMPTS = 64


def to_float32(x):
    """Round a double to the nearest binary32 (ties to even), returned as a Python float."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def mix64(z):
    """SplitMix64's finaliser ("The hash"), modulo 2^64."""
    z &= MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
    return z ^ (z >> 31)


def counter_hash(seed, stream, a, b):
    """counter_hash(seed, stream, a, b) of "The hash": four chained mix64 rounds."""
    g = GOLDEN_GAMMA
    h = mix64(seed + g)
    h = mix64(h + stream + g)
    h = mix64(h + a + g)
    return mix64(h + b + g)


def unit_interval(bits):
    """unit(bits) = ((bits >> 11) + 0.5) * 2^-53, in (0, 1).

    Evaluated as the double operations it is written as: (bits >> 11) < 2^53 converts
    exactly, the + 0.5 rounds to nearest even only when (bits >> 11) >= 2^52, and the scaling by
    a power of two is exact, so this is also the exact value rounded once.
    """
    return (float(bits >> 11) + 0.5) * 2.0 ** -53


def log2_det(x):
    """log2_det of "Lattice values", for a normal positive double x.

    The exponent and the mantissa are taken from the bit pattern, as the page describes them
    (biased exponent - 1023, and x with its exponent field set to that of 1.0).
    """
    bits = struct.unpack("<Q", struct.pack("<d", x))[0]
    biased_exponent = (bits >> 52) & 0x7FF
    if biased_exponent == 0 or biased_exponent == 0x7FF or x <= 0:
        raise ValueError("log2_det is specified for normal positive doubles only: %r" % x)
    e = biased_exponent - 1023
    mantissa_bits = (bits & ~(0x7FF << 52)) | (1023 << 52)
    m = struct.unpack("<d", struct.pack("<Q", mantissa_bits))[0]
    if m > SQRT2:
        m = m * 0.5
        e = e + 1
    y = (m - 1.0) / (m + 1.0)
    y2 = y * y
    series = LOG2_SERIES[11]
    for k in range(10, -1, -1):
        series = series * y2 + LOG2_SERIES[k]
    return float(e) + y * series


def log_det(x):
    """log_det(s) = log2_det(s) * 0.69314718055994531 ("Lattice values")."""
    return log2_det(x) * LN2


def lattice_normal(seed, i, j):
    """Marsaglia's polar method for cell (i, j), in double, before the rounding to float."""
    cell = (j << 32) | i
    for attempt in range(MAX_POLAR_ATTEMPTS):
        v1 = 2.0 * unit_interval(counter_hash(seed, STREAM_LATTICE, cell, 2 * attempt)) - 1.0
        v2 = 2.0 * unit_interval(counter_hash(seed, STREAM_LATTICE, cell, 2 * attempt + 1)) - 1.0
        s = v1 * v1 + v2 * v2
        if s >= 1.0 or s == 0.0:
            continue
        # "v1 · sqrt(−2 · log_det(s) / s)": left to right, (-2 · log) / s under the root.
        return v1 * math.sqrt(-2.0 * log_det(s) / s)
    return 0.0


def lattice_value(seed, i, j):
    """The lattice value L(i, j): the polar method's double rounded to binary32."""
    return to_float32(lattice_normal(seed, i, j))


def make_lattice(seed, size, progress=None):
    """The P x P lattice, row-major: values[j * P + i] ("Lattice values")."""
    if size <= 0 or size & (size - 1):
        raise ValueError("the lattice size P must be a power of two: %r" % size)
    values = []
    for j in range(size):
        for i in range(size):
            values.append(lattice_value(seed, i, j))
        if progress is not None:
            progress(j + 1, size)
    return values


def fnv1a64_of_floats(values):
    """FNV-1a 64 of the values' little-endian binary32 bytes ("Test vectors")."""
    data = struct.pack("<%df" % len(values), *values)
    h = 0xCBF29CE484222325
    for byte in data:
        h = ((h ^ byte) * 0x100000001B3) & MASK64
    return h


def octave_offset(seed, k, axis, size):
    """omega_k of "Per-octave offsets": ((hash >> 40) · 2^−24) · P lattice cells, exact."""
    return (float(counter_hash(seed, STREAM_OCTAVE_OFFSET, k, axis) >> 40) * 2.0 ** -24) * size
