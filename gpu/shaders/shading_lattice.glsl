// The noise lattice S(x) of §2.1 (core/interpolant.h), which the dithered layer transitions
// and the water's waves reuse: the P x P values row-major in a storage buffer, P a power of
// two. Operation order as in the C++ templates.
layout(std430, binding = 1) readonly buffer LatticeBlock {
  int lattice_size;  // P
  int lattice_mask;  // P - 1
  int lattice_pad0, lattice_pad1;
  float lattice_values[];  // values[j * P + i]
};

float lattice_at(int i, int j) { return lattice_values[j * lattice_size + i]; }

// wrap_period: wrap_period.glsl.

struct LatticeCell {
  int i0, j0, i1, j1;
  float fx, fz;
};

LatticeCell locate_cell(float px, float pz) {
  precise float period = float(lattice_size);
  precise float inv_period = divide(1.0, period);  // exact: P is a power of two
  precise float wx = wrap_period(px, period, inv_period);
  precise float wz = wrap_period(pz, period, inv_period);
  precise float fx = floor(wx);
  precise float fz = floor(wz);
  precise float rx = wx - fx;
  precise float rz = wz - fz;
  LatticeCell c;
  c.i0 = int(fx) & lattice_mask;
  c.j0 = int(fz) & lattice_mask;
  c.i1 = (c.i0 + 1) & lattice_mask;
  c.j1 = (c.j0 + 1) & lattice_mask;
  c.fx = rx;
  c.fz = rz;
  return c;
}

float fade_cubic(float t) {
  precise float r = t * t * (3.0 - 2.0 * t);
  return r;
}

float fade_quintic(float t) {
  precise float r = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
  return r;
}

float fade_slope_quintic(float t) {
  precise float r = 30.0 * t * t * (t - 1.0) * (t - 1.0);
  return r;
}

// sample_lattice<kCubic>: the dithering noise.
float sample_lattice_cubic(float px, float pz) {
  const LatticeCell c = locate_cell(px, pz);
  precise float tx = fade_cubic(c.fx);
  precise float tz = fade_cubic(c.fz);
  const float v00 = lattice_at(c.i0, c.j0);
  const float v10 = lattice_at(c.i1, c.j0);
  const float v01 = lattice_at(c.i0, c.j1);
  const float v11 = lattice_at(c.i1, c.j1);
  precise float bottom = v00 + tx * (v10 - v00);
  precise float top = v01 + tx * (v11 - v01);
  precise float r = bottom + tz * (top - bottom);
  return r;
}

// sample_lattice_gradient<kQuintic>: the waves' normal map (§4.3). Only the gradient is used.
void lattice_gradient_quintic(float px, float pz, out float dpx, out float dpz) {
  const LatticeCell c = locate_cell(px, pz);
  precise float tx = fade_quintic(c.fx);
  precise float tz = fade_quintic(c.fz);
  const float v00 = lattice_at(c.i0, c.j0), v10 = lattice_at(c.i1, c.j0);
  const float v01 = lattice_at(c.i0, c.j1), v11 = lattice_at(c.i1, c.j1);
  precise float bottom = v00 + tx * (v10 - v00);
  precise float top = v01 + tx * (v11 - v01);
  precise float slope_bottom = v10 - v00, slope_top = v11 - v01;
  precise float gx = fade_slope_quintic(c.fx) * (slope_bottom + tz * (slope_top - slope_bottom));
  precise float gz = fade_slope_quintic(c.fz) * (top - bottom);
  dpx = gx;
  dpz = gz;
}
