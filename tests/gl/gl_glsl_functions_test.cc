// The GLSL ports of core's deterministic functions (gpu/shaders/common.glsl: log2_det,
// exp2_det, normalize_or; gpu/shaders/det_trig.glsl.in: sin_cos_det, atan2_det) against the C++
// originals through a compute shader: bit for bit where they use + - * only, and where this GL
// divides and takes square roots as the CPU does (llvmpipe: tests/gl/gl_arithmetic.h); on a GL
// that uses GLSL 4.50's allowance (a / b 2.5 ULP, sqrt 4.5 units: an NVIDIA GPU), within the
// bound that allowance gives each function, derived at the check.
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/vec3.h"
#include "gpu/gl_program.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_shader_sources.h"
#include "gpu/glsl_sources.h"
#include "tests/gl/gl_arithmetic.h"
#include "tests/gl/gl_compute_run.h"
#include "tests/gl/gl_test_context.h"
#include "tests/oracles/gl_interpolation_bound.h"

namespace relief {
namespace {

using test::kFloatUnit;

// A float result's ulp (tests/oracles/gl_interpolation_bound.h).
double ulp(double x) {
  return test::float_ulp(x);
}

// Which GLSL library the test shader is built with.
enum class Library {
  kShading,  // stage 8's prelude and common.glsl
  kTerrain,  // the terrain stages' prelude and det_math.glsl
};

// Runs `body` (GLSL statements reading float x = in_values[i], writing out_values[3 i + c])
// over `inputs` in a compute shader with `library`; returns the outputs.
std::vector<float> run_glsl(const std::string& body, const std::vector<float>& inputs,
                            int outputs_per_input, Library library = Library::kShading) {
  const std::string main = R"(
void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) { return; }
  const float x = in_values[i];
)" + body + "\n}\n";
  const bool terrain = library == Library::kTerrain;
  const std::string prelude = terrain ? gpu::shader_prelude() : gpu::glsl_prelude();
  // Both libraries take log2_det from the one log2_det.glsl, each under its own prelude.
  const std::string functions =
      (terrain ? std::string(gpu::shader_file("det_math.glsl")) : std::string(gpu::glsl::kCommon)) +
      std::string(gpu::glsl::kLog2Det);
  return test::run_compute(prelude, functions, main, inputs, inputs.size(),
                           inputs.size() * std::size_t(outputs_per_input));
}

// Positive normal floats spread over the exponent range, and values near 1 and sqrt(2).
std::vector<float> log_inputs() {
  std::vector<float> x;
  for (std::uint32_t bits = 0x00800000u; bits < 0x7f000000u; bits += 0x000fffffu) {
    x.push_back(std::bit_cast<float>(bits));
  }
  for (int k = -2000; k <= 2000; ++k) {
    x.push_back(1.0f + float(k) * 1e-4f);
    x.push_back(1.41421356f + float(k) * 1e-6f);
  }
  return x;
}

// log2_det's one inexact operation on a GL is y = (m - 1) / (m + 1) (m - 1 exact by Sterbenz,
// m + 1 correctly rounded on both): the GL's y lies within 2.5 units (3 in the compute stages,
// formed in double and rounded to float) + the CPU's 0.5 of the CPU's. The
// rest, e + y S(y^2), is the same float function G of y on both sides: |G(y') - G(y)| <=
// L |y' - y| + 2 E, with L = max |g'| = (2 / ln 2) / (1 - y^2) <= 2.973 (|y| <= 0.1716) and E
// the float evaluation error of G at one point: the Horner sum S (<= 2.92) within 9 roundings
// of 2^-24, times y one more: 14.6 units of |y|, and the last addition half an ulp of the
// result. In all: 2.973 * 3.5 + 2 * 14.6 <= 40 units of |y|, and one ulp of the result.
double log2_det_bound(float x, float cpu) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  double m = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u);
  if (m > double(float(1.41421356237309505))) {
    m *= 0.5;
  }
  const double y = (m - 1) / (m + 1);
  return 40 * kFloatUnit * std::abs(y) + ulp(cpu);
}

TEST_CASE("glslLog2DetIsTheCppLog2DetWithinGlslsDivisionAllowance", "[gl]") {
  const std::vector<float> x = log_inputs();
  // The compute stages' division is correctly rounded, the draw's the GL's own
  // (gpu/glsl_rounding.h): each library against the CPU, bit for bit where its division is.
  for (const Library library : {Library::kShading, Library::kTerrain}) {
    const std::vector<float> gl = run_glsl("out_values[i] = log2_det(x);", x, 1, library);
    const bool exact = library == Library::kTerrain ? test::gl_arithmetic().exact()
                                                    : test::gl_arithmetic().draw_exact();
    std::size_t differ = 0, beyond = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const float cpu = log2_det(x[k]);
      differ += std::bit_cast<std::uint32_t>(gl[k]) != std::bit_cast<std::uint32_t>(cpu);
      beyond += !(std::abs(double(gl[k]) - cpu) <= log2_det_bound(x[k], cpu));
    }
    INFO((library == Library::kTerrain ? "compute stages: " : "draw: ")
         << differ << " of " << x.size() << " differ, " << beyond << " beyond the bound");
    CHECK(beyond == 0);
    if (exact) {
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("glslExp2DetIsTheCppExp2DetBitForBit", "[gl]") {
  std::vector<float> x;
  for (int k = -140000; k <= 140000; k += 7) {
    x.push_back(float(k) * 1e-3f);
  }
  const std::vector<float> gl = run_glsl("out_values[i] = exp2_det(x);", x, 1);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    differ += std::bit_cast<std::uint32_t>(gl[k]) != std::bit_cast<std::uint32_t>(exp2_det(x[k]));
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslNormalizeOrIsTheCppNormalizeOrWithinGlslsSqrtAllowance", "[gl]") {
  std::vector<float> x;
  for (int k = 0; k < 20000; ++k) {
    x.push_back(float(k) * 0.37f - 3000.0f);
  }
  const std::string body = R"(
  const vec3 v = vec3(x, 0.5 * x - 7.0, 3.0 - 0.25 * x);
  const vec3 n = normalize_or(v, vec3(0.0, 1.0, 0.0));
  out_values[3u * i] = n.x;
  out_values[3u * i + 1u] = n.y;
  out_values[3u * i + 2u] = n.z;)";
  const std::vector<float> gl = run_glsl(body, x, 3);
  // v * (1 / sqrt(|v|^2)), |v|^2 the same on both sides: the GL's square root within
  // kSpecSqrtUnits, its division 2.5 units (each half a unit more where formed in double and
  // rounded) and its product half a unit; the CPU's three roundings half a unit each: each
  // component within 10 units of its size (and the second order).
  const double units = test::kSpecSqrtUnits + test::kSpecDivisionUnits +
                       2 * test::kConversionUnits + 0.5 + 3 * 0.5 + 1e-3;
  std::size_t differ = 0, beyond = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const float v = x[k];
    const Vec3<float> n =
        normalize_or(Vec3<float>{v, 0.5f * v - 7.0f, 3.0f - 0.25f * v}, Vec3<float>{0, 1, 0});
    differ += gl[3 * k] != n.x || gl[3 * k + 1] != n.y || gl[3 * k + 2] != n.z;
    for (int c = 0; c < 3; ++c) {
      const double cpu = c == 0 ? n.x : (c == 1 ? n.y : n.z);
      beyond += !(std::abs(double(gl[3 * k + c]) - cpu) <= units * kFloatUnit * std::abs(cpu));
    }
  }
  INFO(differ << " of " << x.size() << " differ, " << beyond << " components beyond the bound");
  CHECK(beyond == 0);
  if (test::gl_arithmetic().draw_exact()) {  // the draw's common.glsl
    CHECK(differ == 0);
  }
}

TEST_CASE("glslSinCosDetIsTheCppSinCosDetBitForBit", "[gl][planet]") {
  // The bend's and the sky's range (central angles up to pi, nadir angles), the reduction's
  // quadrant boundaries, tiny arguments, and out to the clamp of the reduction (|x| > 64 pi/2).
  std::vector<float> x;
  for (int k = -120000; k <= 120000; k += 3) {
    x.push_back(float(k) * 1e-3f);
  }
  for (int q = -8; q <= 8; ++q) {
    for (int k = -50; k <= 50; ++k) {
      x.push_back(float(q) * 1.57079633f + float(k) * 1e-6f);
    }
  }
  for (float v = 1e-30f; v < 1e-2f; v *= 1.7f) {
    x.push_back(v);
    x.push_back(-v);
  }
  x.push_back(0.0f);
  const std::string body = R"(
  float s, c;
  sin_cos_det(x, s, c);
  out_values[3u * i] = s;
  out_values[3u * i + 1u] = c;
  out_values[3u * i + 2u] = sin_det(x);)";
  const std::vector<float> gl = run_glsl(body, x, 3, Library::kTerrain);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    float s = 0, c = 0;
    sin_cos_det(x[k], s, c);
    differ += std::bit_cast<std::uint32_t>(gl[3 * k]) != std::bit_cast<std::uint32_t>(s) ||
              std::bit_cast<std::uint32_t>(gl[3 * k + 1]) != std::bit_cast<std::uint32_t>(c) ||
              std::bit_cast<std::uint32_t>(gl[3 * k + 2]) != std::bit_cast<std::uint32_t>(s);
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslAtan2DetIsTheCppAtan2DetWithinGlslsDivisionAllowance", "[gl][planet]") {
  // y >= 0 (the domain), x of both signs: every octant boundary (t = tan(pi/8), y = |x|, x = 0)
  // and the (0, 0) guard.
  std::vector<float> ys, xs;
  for (int a = 0; a <= 400; ++a) {
    for (int b = -400; b <= 400; b += 3) {
      ys.push_back(float(a) * 0.0125f);
      xs.push_back(float(b) * 0.0125f);
    }
  }
  for (int k = -100; k <= 100; ++k) {
    ys.push_back(0.41421356f + float(k) * 1e-7f);  // t near tan(pi/8)
    xs.push_back(1.0f);
    ys.push_back(1.0f + float(k) * 1e-7f);  // y near |x|
    xs.push_back(-1.0f);
  }
  ys.push_back(3e-30f);
  xs.push_back(-2e-30f);
  // The pairs lie interleaved in the input (y, x, y, x, ...): an even invocation reads its
  // pair, an odd one writes 0.
  std::vector<float> packed;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    packed.push_back(ys[k]);
    packed.push_back(xs[k]);
  }
  const std::string body = R"(
  out_values[i] = (i & 1u) == 0u ? atan2_det(x, in_values[i + 1u]) : 0.0;)";
  const std::vector<float> gl = run_glsl(body, packed, 1, Library::kTerrain);
  // Both sides lie within 3.5 ulp of atan2 of the same floats (core/det_math.h) but for the
  // GL's divisions: t = lo / hi and u = (t - 1) / (t + 1) within 3 units (2.5, and the compute
  // stages' rounding from double) instead of half a unit: 2.5 units more of t and of u, which
  // reach the angle with a gain of at most 1 (|atan'| <= 1, |du/dt| = 2 / (t + 1)^2 <= 1 above
  // tan(pi/8)): |GL - CPU| <= 7 ulp + 2.5 (t + |u|) units.
  std::size_t differ = 0, beyond = 0;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const float cpu = atan2_det(ys[k], xs[k]);
    differ += std::bit_cast<std::uint32_t>(gl[2 * k]) != std::bit_cast<std::uint32_t>(cpu);
    const double ax = std::abs(double(xs[k])), y = ys[k];
    const double t = std::max(ax, y) > 0 ? std::min(ax, y) / std::max(ax, y) : 0.0;
    const double u = std::abs((t - 1) / (t + 1));
    const double bound = 7 * ulp(cpu) + 2.5 * kFloatUnit * (t + u);
    beyond += !(std::abs(double(gl[2 * k]) - cpu) <= bound);
  }
  INFO(differ << " of " << ys.size() << " differ, " << beyond << " beyond the bound");
  CHECK(beyond == 0);
  if (test::gl_arithmetic().exact()) {
    CHECK(differ == 0);
  }
}

}  // namespace
}  // namespace relief
