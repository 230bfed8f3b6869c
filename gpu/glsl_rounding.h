// How the GLSL programs divide and take float square roots: every shader calls divide(a, b)
// and square_root(x) where the CPU divides or takes a float square root, and each prelude
// defines them (gl_shader_prelude.cc for the compute stages, glsl_prelude.cc for the draw).
//
// GLSL 4.50 (§4.7.1) lets a / b and 1.0 / b be 2.5 ULP off and sqrt inherit the error of
// 1.0 / inversesqrt(), and an NVIDIA GPU uses that allowance (docs/gl-backend.md gives the
// errors measured on an H100; tests/gl/gl_arithmetic.h measures them on every GL the tests
// run on): the GL's stages left the CPU's bits at every division, and the terrain drifted from
// the CPU's by whatever the later stages made of that.
//
// The compute stages (1-4) therefore divide and take square roots correctly rounded: formed in
// double and rounded once to float. A float quotient or square root lies at least about 2^-49
// relative from a midpoint of two floats, far beyond the double operation's error of a few
// double ulps, and double rounding is innocuous from 53 >= 2 x 24 + 2 bits (Figueroa 1995): the
// result is the IEEE 754 one, the CPU's, wherever the GL's double division and square root are
// accurate to a few double ulps (GLSL promises double operations only single precision; the
// tests measure it). On the H100 this made stages 1-4 bit-identical to the CPU's and cost
// nothing measurable (0.14 ms for all of them). The argument holds for results in float's
// normal range: a quotient beyond it (double to float is undefined in GLSL when out of range)
// or subnormal (which a GL may flush) is not the CPU's; the stages divide nothing of that size
// (their domains are stated at each division), and the tests' operands stay inside it.
//
// The draw keeps the GL's own float division and square root: the same correctly rounded
// functions took the H100's terrain draw from 8.3 to 30.5 ms of GPU time (fp64 in a fragment
// shader), and the frames' remaining differences come from rasterisation, not from the
// shading's divisions (docs/gl-backend.md, "On a GPU"). The double overloads are the GL's own
// double operations on both sides (det_trig.glsl.in's double twin, a planet's sky).
#pragma once

namespace relief::gpu {

// The compute stages' definitions.
inline constexpr const char* kCorrectlyRoundedGlsl = R"(
float divide(float a, float b) {
  precise double q = double(a) / double(b);
  return float(q);
}
double divide(double a, double b) {
  precise double q = a / b;
  return q;
}
float square_root(float x) {
  precise double r = sqrt(double(x));
  return float(r);
}
double square_root(double x) {
  precise double r = sqrt(x);
  return r;
}
)";

// The draw programs' definitions: the GL's own operations.
inline constexpr const char* kGlRoundedGlsl = R"(
float divide(float a, float b) {
  precise float q = a / b;
  return q;
}
double divide(double a, double b) {
  precise double q = a / b;
  return q;
}
float square_root(float x) {
  precise float r = sqrt(x);
  return r;
}
double square_root(double x) {
  precise double r = sqrt(x);
  return r;
}
)";

}  // namespace relief::gpu
