// This GL's float arithmetic against the GLSL 4.50 specification's precision rules (§4.7.1,
// §4.7.2), which every bound of the [gl] tests builds on (tests/gl/gl_arithmetic.h). The
// figures it prints are the measured errors docs/gl-backend.md reports for each GL.
#include <catch2/catch.hpp>

#include "tests/gl/gl_arithmetic.h"

namespace relief {
namespace {

TEST_CASE("thisGlRoundsWithinTheGlslSpecificationsPrecisionRules", "[gl]") {
  const test::GlArithmetic& a = test::gl_arithmetic();
  INFO(test::gl_context().renderer()
       << ", " << a.inputs << " inputs: a / b " << a.division_ulps << " ulp, 1 / b "
       << a.reciprocal_ulps << " ulp, sqrt " << a.sqrt_ulps << " ulp (" << a.sqrt_units
       << " units), inversesqrt " << a.inversesqrt_ulps << " ulp; divides as the CPU "
       << a.divides_as_cpu << ", sqrt as the CPU " << a.sqrt_as_cpu);
  WARN("GL arithmetic: a / b " << a.division_ulps << " ulp, 1 / b " << a.reciprocal_ulps
                               << " ulp, sqrt " << a.sqrt_ulps << " ulp, inversesqrt "
                               << a.inversesqrt_ulps
                               << " ulp; the stages' divide, square_root as the CPU: "
                               << a.stage_divide_as_cpu << ", " << a.stage_sqrt_as_cpu
                               << "; double + - * / sqrt as the CPU: " << a.double_as_cpu);
  // Correctly rounded: + - * (and the conversions the probe's literals take).
  CHECK(a.basic_as_cpu);
  // precise: a * b + c in two roundings, never one FMA.
  CHECK(a.precise_unfused);
  CHECK(a.division_ulps <= test::kSpecDivisionUnits);
  CHECK(a.reciprocal_ulps <= test::kSpecDivisionUnits);
  CHECK(a.inversesqrt_ulps <= test::kSpecInverseSqrtUnits);
  CHECK(a.sqrt_units <= test::kSpecSqrtUnits);
  // What the CPU's bits mean: a GL that divides as the CPU rounds correctly.
  if (a.divides_as_cpu) {
    CHECK(a.division_ulps <= 0.5);
  }
  if (a.sqrt_as_cpu) {
    CHECK(a.sqrt_ulps <= 0.5);
  }
}

}  // namespace
}  // namespace relief
