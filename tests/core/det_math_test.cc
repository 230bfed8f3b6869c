#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Distance in units in the last place of the float nearest the exact value.
double float_ulps(float value, long double exact) {
  const float nearest = static_cast<float>(exact);
  const float next = std::nextafter(nearest, std::numeric_limits<float>::infinity());
  const double ulp = static_cast<double>(next) - static_cast<double>(nearest);
  return std::abs(static_cast<long double>(value) - exact) / ulp;
}

double double_ulps(double value, long double exact) {
  const double nearest = static_cast<double>(exact);
  const double ulp = std::nextafter(nearest, std::numeric_limits<double>::infinity()) - nearest;
  return static_cast<double>(std::abs(static_cast<long double>(value) - exact) / ulp);
}

TEST_CASE("log2DetIsWithinThreeUlpsForFloatOverTheWholeRange", "[det_math]") {
  test::TestRandom random(7);
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    // Uniform in the exponent: every binade, subnormals included.
    const float x = static_cast<float>(std::exp2(random.uniform(-149.0, 127.9)));
    if (!(x > 0.0f)) {
      continue;
    }
    const long double exact = std::log2(static_cast<long double>(x));
    if (exact == 0) {
      CHECK(log2_det(x) == 0.0f);
      continue;
    }
    worst = std::max(worst, float_ulps(log2_det(x), exact));
  }
  CHECK(worst <= 3.0);
}

TEST_CASE("log2DetIsWithinTwoUlpsForDouble", "[det_math]") {
  test::TestRandom random(11);
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    const double x = std::exp2(random.uniform(-1074.0, 1023.9));
    if (!(x > 0.0)) {
      continue;
    }
    const long double exact = std::log2(static_cast<long double>(x));
    if (exact != 0) {
      worst = std::max(worst, double_ulps(log2_det(x), exact));
    }
  }
  CHECK(worst <= 2.0);
}

TEST_CASE("log2DetIsExactOnPowersOfTwo", "[det_math]") {
  for (int e = -149; e <= 127; ++e) {
    CHECK(log2_det(std::ldexp(1.0f, e)) == static_cast<float>(e));
  }
  for (int e = -1074; e <= 1023; ++e) {
    CHECK(log2_det(std::ldexp(1.0, e)) == static_cast<double>(e));
  }
}

TEST_CASE("logDetMatchesTheNaturalLogarithm", "[det_math]") {
  for (double x : {1e-300, 1e-5, 0.3, 0.999999, 1.0, 1.000001, 2.5, 1e8, 1e300}) {
    CHECK(log_det(x) == Approx(std::log(x)).epsilon(1e-15).margin(1e-300));
  }
}

TEST_CASE("log2DetIsMonotonic", "[det_math]") {
  // Monotonicity matters for the LOD: a larger spacing must never give more octaves.
  float x = 0.5f;
  float previous = log2_det(x);
  for (int k = 0; k < 100000; ++k) {
    x = std::nextafter(x, 2.0f);
    const float current = log2_det(x);
    REQUIRE(current >= previous);
    previous = current;
  }
}

}  // namespace
}  // namespace relief
