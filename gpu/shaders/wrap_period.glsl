// p mod P in [0, P] (core/interpolant.h, wrap_period): every operation exact but the last
// subtraction for p in (-P/2, 0), which the CPU rounds the same way. Shared by the compute
// stages' lattice (lattice.glsl, octave_coordinates.glsl) and the draw programs' shading
// lattice (shading_lattice.glsl).
float wrap_period(float p, float period, float inv_period) {
  precise float wrapped = p - period * floor(p * inv_period);
  return wrapped;
}
