// Division and square root rounded as IEEE 754 (and the CPU) round them, for every GLSL
// program: both preludes (gl_shader_prelude.cc for the compute stages, glsl_prelude.cc for the
// draw) end with these functions, and the shaders call div_cr and sqrt_cr wherever the CPU
// divides or takes a float square root.
//
// Why: GLSL 4.50 (§4.7.1) lets a / b and 1.0 / b be 2.5 ULP off and sqrt inherit the error
// of 1.0 / inversesqrt(), and an NVIDIA GPU uses that allowance (docs/gl-backend.md gives the
// errors measured on an H100; tests/gl/gl_arithmetic.h), so the GL's stages left the CPU's bits at
// every division and its frames drifted from the CPU's by whatever the shading made of that.
// A float quotient or square root formed in double and rounded once to float is the correctly
// rounded float result: the double operation's error (at most a few ulp of double) is far
// below the least distance, about 2^-49 relative, between a float quotient or square root and
// a midpoint of two floats (and double rounding is innocuous from 53 >= 2 x 24 + 2 bits,
// Figueroa 1995). That holds where the GL's double division and square root are accurate to a
// few double ulp; GLSL promises double operations only single precision, so
// tests/gl/gl_arithmetic.h measures div_cr and sqrt_cr on every GL the tests run on.
// The double overloads are the GL's own double operations (det_trig.glsl.in's double twin).
#pragma once

namespace relief::gpu {

inline constexpr const char* kCorrectlyRoundedGlsl = R"(
float div_cr(float a, float b) {
  precise double q = double(a) / double(b);
  return float(q);
}
double div_cr(double a, double b) {
  precise double q = a / b;
  return q;
}
float sqrt_cr(float x) {
  precise double r = sqrt(double(x));
  return float(r);
}
double sqrt_cr(double x) {
  precise double r = sqrt(x);
  return r;
}
)";

}  // namespace relief::gpu
