// The interpolated lattice S of §2.1 (core/interpolant.h), operation by operation. The lattice
// is the CPU's NoiseLattice: its size and mask, then its values row-major (values[j P + i]),
// the header laid out as GlLatticeHeader (gpu/gl_terrain.h).
layout(std430, binding = RELIEF_BINDING_LATTICE) readonly buffer LatticeBlock {
  int lattice_size;
  int lattice_mask;
  float lattice_values[];
};

// wrap_period: wrap_period.glsl.

// The three fade curves of core/interpolant.h; `kind` is FbmParams::interpolant
// (0 linear, 1 cubic, 2 quintic).
float fade(int kind, float t) {
  precise float f = t;
  if (kind == 1) {
    f = t * t * (3.0 - 2.0 * t);
  } else if (kind == 2) {
    f = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
  }
  return f;
}

// sample_lattice: locate_cell, then the lerps a + w (b - a), along x first.
float sample_lattice(int kind, float px, float pz) {
  precise float period = float(lattice_size);
  precise float inv_period = divide(1.0, period);  // exact: P is a power of two
  precise float wx = wrap_period(px, period, inv_period);
  precise float wz = wrap_period(pz, period, inv_period);
  precise float fx = floor(wx);
  precise float fz = floor(wz);
  const int i0 = int(fx) & lattice_mask;
  const int j0 = int(fz) & lattice_mask;
  const int i1 = (i0 + 1) & lattice_mask;
  const int j1 = (j0 + 1) & lattice_mask;
  precise float tx = fade(kind, wx - fx);
  precise float tz = fade(kind, wz - fz);
  const float v00 = lattice_values[j0 * lattice_size + i0];
  const float v10 = lattice_values[j0 * lattice_size + i1];
  const float v01 = lattice_values[j1 * lattice_size + i0];
  const float v11 = lattice_values[j1 * lattice_size + i1];
  precise float bottom = v00 + tx * (v10 - v00);
  precise float top = v01 + tx * (v11 - v01);
  precise float s = bottom + tz * (top - bottom);
  return s;
}
