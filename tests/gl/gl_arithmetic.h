// This GL's float arithmetic, measured on it against the CPU's IEEE arithmetic: the premise of
// every bound the [gl] tests derive. The GLSL 4.50 specification (§4.7.1, "Range and
// Precision") requires + - * and conversions to be correctly rounded, and allows a / b and
// 1.0 / b 2.5 ULP, inversesqrt 2 ULP and sqrt what 1.0 / inversesqrt() gives; §4.7.2's
// `precise` forbids fusing a * b + c into one operation. Mesa's llvmpipe divides and takes
// square roots correctly rounded (the CPU's bits); an NVIDIA GPU does not. The compute stages
// therefore divide and take square roots correctly rounded (gpu/glsl_rounding.h: formed in
// double and rounded once, the CPU's bits wherever the GL's double operations are accurate,
// which GLSL does not promise), the draw with the GL's own. A test that pins the CPU's bits
// where a shader divides does so only where gl_arithmetic() measured that shader's division to
// give them, and otherwise checks the bound the specification's allowance gives.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/gl_shader_prelude.h"
#include "tests/gl/gl_compute_run.h"
#include "tests/gl/gl_test_context.h"
#include "tests/support/hashed_draws.h"

namespace relief::test {

// The largest relative spacing of floats: ulp(x) <= kFloatUnit |x| for every normal x, so an
// allowance of k ULP is at most k kFloatUnit relative.
inline constexpr double kFloatUnit = 0x1.0p-23;

// GLSL 4.50 §4.7.1's allowances in kFloatUnit of the exact result.
inline constexpr double kSpecDivisionUnits = 2.5;
inline constexpr double kSpecInverseSqrtUnits = 2.0;
// sqrt "inherited from 1.0 / inversesqrt()": 2 then 2.5, and the second order of
// (1 + 2.5u) / (1 - 2u) (5u^2 + 4u^2).
inline constexpr double kSpecSqrtUnits = 4.5 + 9.0 * kFloatUnit;
// The compute stages' division and square root are formed in double and rounded to float
// (gpu/glsl_rounding.h); where the GL's double operations are no better than GLSL promises
// (single precision), the rounding to float adds half a unit to the allowances above.
inline constexpr double kConversionUnits = 0.5;

struct GlArithmetic {
  // Largest error over the probe's inputs, in ulps of the exact result (0.5: correctly rounded).
  double division_ulps = 0, reciprocal_ulps = 0, sqrt_ulps = 0, inversesqrt_ulps = 0;
  // The same, relative to the exact result, in kFloatUnit.
  double division_units = 0, reciprocal_units = 0, sqrt_units = 0, inversesqrt_units = 0;
  // Whether the built-in a / b and sqrt gave the CPU's float bits on every input.
  bool divides_as_cpu = true, sqrt_as_cpu = true;
  // Whether the compute stages' divide (a / b and 1 / b) and square_root did
  // (gpu/glsl_rounding.h; the draw's are the built-ins above).
  bool stage_divide_as_cpu = true, stage_sqrt_as_cpu = true;
  // + - * and float(double) gave the CPU's bits on every input (GLSL: correctly rounded).
  bool basic_as_cpu = true;
  // A precise a * b + c gave float(float(a * b) + c) on every input (not fused).
  bool precise_unfused = true;
  // double + - * / sqrt, a precise double a * b + c (not fused) and double(float) gave the
  // CPU's double bits on every input (IEEE's correctly rounded results; GLSL 4.50 promises
  // double operations only the precision of float).
  bool double_as_cpu = true;
  std::size_t inputs = 0;

  // The compute stages' division and square roots as the CPU's: GLSL functions built of them
  // keep the CPU's bits there.
  bool exact() const { return stage_divide_as_cpu && stage_sqrt_as_cpu; }
  // The same for the draw programs, which divide with the GL's own operations.
  bool draw_exact() const { return divides_as_cpu && sqrt_as_cpu; }
};

namespace detail {

// The ulp of the binade of a real result (not tests/oracles' float_ulp, the spacing above the
// float nearest it, twice as large where the result rounds up to a power of two): what
// GLSL's "ULP" of a result is measured in.
inline double binade_ulp(double exact) {
  int exponent = 0;
  std::frexp(std::abs(exact), &exponent);  // |exact| in [2^(exponent-1), 2^exponent)
  return std::ldexp(1.0, std::max(exponent - 1, -126) - 23);
}

// A float of magnitude in [2^lo, 2^hi), either sign, mantissa uniform.
inline float draw_float(HashedDraws& draws, int lo, int hi) {
  const double mantissa = draws.uniform(1.0, 2.0);
  const int exponent = int(std::floor(draws.uniform(lo, hi)));
  const float sign = draws.uniform(0.0, 1.0) < 0.5 ? -1.0f : 1.0f;
  return sign * static_cast<float>(std::ldexp(mantissa, exponent));
}

inline GlArithmetic measure_gl_arithmetic() {
  const std::string main = R"(
void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint count = u_count;
  if (i >= count) { return; }
  const float a = in_values[3u * i], b = in_values[3u * i + 1u], c = in_values[3u * i + 2u];
  precise float quotient = a / b;
  precise float reciprocal = 1.0 / b;
  precise float root = sqrt(abs(a));
  precise float inverse_root = inversesqrt(abs(a));
  precise float sum = a + c;
  precise float difference = a - c;
  precise float product = a * b;
  precise float unfused = a * b + c;
  precise float quotient_cr = divide(a, b);
  precise float reciprocal_cr = divide(1.0, b);
  precise float root_cr = square_root(abs(a));
  out_values[8u * i] = quotient;
  out_values[8u * i + 1u] = reciprocal;
  out_values[8u * i + 2u] = root;
  out_values[8u * i + 3u] = inverse_root;
  out_values[8u * i + 4u] = sum;
  out_values[8u * i + 5u] = difference;
  out_values[8u * i + 6u] = product;
  out_values[8u * i + 7u] = unfused;
  out_values[8u * count + 3u * i] = quotient_cr;
  out_values[8u * count + 3u * i + 1u] = reciprocal_cr;
  out_values[8u * count + 3u * i + 2u] = root_cr;
  // Doubles with all their mantissa bits (the sums round as IEEE's would on an exact GL).
  precise double da = double(a) + double(c) * 0.0009765625LF;
  precise double db = double(b) + double(a) * 0.00000095367431640625LF;
  precise double dq = da / db;
  precise double dr = sqrt(abs(da));
  precise double dp = da * db;
  precise double df = da * db + double(c);
  const double results[5] = double[](da, db, dq, dr, df);
  for (uint k = 0u; k < 5u; ++k) {
    const uvec2 words = unpackDouble2x32(results[k]);
    out_values[11u * count + 10u * i + 2u * k] = uintBitsToFloat(words.x);
    out_values[11u * count + 10u * i + 2u * k + 1u] = uintBitsToFloat(words.y);
  }
}
)";
  // Operands whose quotients, products and sums stay normal (GLSL may flush subnormals) and
  // whose divisors lie in the range the allowance covers, [2^-126, 2^126].
  HashedDraws draws(0x61726974686d);
  std::vector<float> in;
  const std::size_t count = 1 << 16;
  for (std::size_t k = 0; k < count; ++k) {
    in.push_back(draw_float(draws, -40, 40));
    in.push_back(draw_float(draws, -40, 40));
    in.push_back(draw_float(draws, -40, 40));
  }
  const std::vector<float> out =
      run_compute(gpu::shader_prelude(), "", main, in, count, 21 * count);

  GlArithmetic r;
  r.inputs = count;
  const auto same = [](float x, float y) {
    return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(y);
  };
  const auto record = [](double gl, double exact, double& ulps, double& units) {
    const double error = std::abs(gl - exact);
    ulps = std::max(ulps, error / binade_ulp(exact));
    units = std::max(units, error / (std::abs(exact) * kFloatUnit));
  };
  for (std::size_t k = 0; k < count; ++k) {
    const float a = in[3 * k], b = in[3 * k + 1], c = in[3 * k + 2];
    const float* g = &out[8 * k];
    const double abs_a = std::abs(double(a));
    record(g[0], double(a) / double(b), r.division_ulps, r.division_units);
    record(g[1], 1.0 / double(b), r.reciprocal_ulps, r.reciprocal_units);
    record(g[2], std::sqrt(abs_a), r.sqrt_ulps, r.sqrt_units);
    record(g[3], 1.0 / std::sqrt(abs_a), r.inversesqrt_ulps, r.inversesqrt_units);
    r.divides_as_cpu = r.divides_as_cpu && same(g[0], a / b) && same(g[1], 1.0f / b);
    r.sqrt_as_cpu = r.sqrt_as_cpu && same(g[2], std::sqrt(std::abs(a)));
    r.basic_as_cpu = r.basic_as_cpu && same(g[4], a + c) && same(g[5], a - c) && same(g[6], a * b);
    const float product = a * b;
    r.precise_unfused = r.precise_unfused && same(g[7], product + c);
    const float* cr = &out[8 * count + 3 * k];
    r.stage_divide_as_cpu = r.stage_divide_as_cpu && same(cr[0], a / b) && same(cr[1], 1.0f / b);
    r.stage_sqrt_as_cpu = r.stage_sqrt_as_cpu && same(cr[2], std::sqrt(std::abs(a)));
    const double da = double(a) + double(c) * 0.0009765625;
    const double db = double(b) + double(a) * 0.00000095367431640625;
    const double dp = da * db;
    const double df = dp + double(c);
    const double expected[5] = {da, db, da / db, std::sqrt(std::abs(da)), df};
    const float* words = &out[11 * count + 10 * k];
    for (int j = 0; j < 5; ++j) {
      const std::uint64_t bits = std::uint64_t(std::bit_cast<std::uint32_t>(words[2 * j])) |
                                 std::uint64_t(std::bit_cast<std::uint32_t>(words[2 * j + 1]))
                                     << 32;
      r.double_as_cpu = r.double_as_cpu && bits == std::bit_cast<std::uint64_t>(expected[j]);
    }
  }
  return r;
}

}  // namespace detail

// Measured once per process, on the test context.
inline const GlArithmetic& gl_arithmetic() {
  static const GlArithmetic measured = detail::measure_gl_arithmetic();
  return measured;
}

}  // namespace relief::test
