#include <cmath>

#include <catch2/catch.hpp>

#include "core/interpolant.h"
#include "core/lattice.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

const NoiseLattice& lattice16() {
  static const NoiseLattice lattice = make_noise_lattice(3, 16);
  return lattice;
}

constexpr Interpolant kAll[] = {Interpolant::kLinear, Interpolant::kCubic, Interpolant::kQuintic};

TEST_CASE("interpolantsPassThroughLatticeValuesExactly", "[interpolant]") {
  const NoiseLattice& l = lattice16();
  for (Interpolant kind : kAll) {
    for (int j = -16; j < 32; ++j) {
      for (int i = -16; i < 32; ++i) {
        const float expected = l.at(i & l.mask, j & l.mask);
        REQUIRE(sample_lattice<float>(l, kind, float(i), float(j)) == expected);
        REQUIRE(sample_lattice<double>(l, kind, double(i), double(j)) == double(expected));
      }
    }
  }
}

TEST_CASE("interpolantsArePeriodicInBothAxes", "[interpolant]") {
  const NoiseLattice& l = lattice16();
  test::TestRandom random(5);
  for (Interpolant kind : kAll) {
    for (int k = 0; k < 2000; ++k) {
      // Coordinates on a 1/1024 grid: p + m P is exact, so periodicity must be exact too.
      const double px = std::round(random.uniform(0, 16) * 1024) / 1024;
      const double pz = std::round(random.uniform(0, 16) * 1024) / 1024;
      const double s = sample_lattice<double>(l, kind, px, pz);
      for (int m : {-3, -1, 1, 7, 1000000}) {
        REQUIRE(sample_lattice<double>(l, kind, px + 16.0 * m, pz) == s);
        REQUIRE(sample_lattice<double>(l, kind, px, pz - 16.0 * m) == s);
      }
    }
  }
}

TEST_CASE("interpolantsStayWithinTheLatticeExtremes", "[interpolant]") {
  const NoiseLattice& l = lattice16();
  test::TestRandom random(9);
  for (Interpolant kind : kAll) {
    for (int k = 0; k < 20000; ++k) {
      const float s = sample_lattice<float>(l, kind, float(random.uniform(-40, 40)),
                                            float(random.uniform(-40, 40)));
      REQUIRE(s >= l.min_value);
      REQUIRE(s <= l.max_value);
    }
  }
}

// One-sided difference quotients of order `order` at lattice line x = n, from the left and
// from the right, along x at height z.
double one_sided_derivative(Interpolant kind, int order, double n, double z, double side) {
  const NoiseLattice& l = lattice16();
  const double h = 1e-5 * side;
  auto s = [&](double x) { return sample_lattice<double>(l, kind, x, z); };
  if (order == 0) {
    return s(n + h);
  }
  if (order == 1) {
    return (s(n + 2 * h) - s(n + h)) / h;  // derivative at n + 1.5 h
  }
  return (s(n + 3 * h) - 2 * s(n + 2 * h) + s(n + h)) / (h * h);  // second derivative
}

// Is the function C^order across every lattice line (x = n) at a few heights?
bool continuous_across_lattice_lines(Interpolant kind, int order, double tolerance) {
  for (int n = 1; n < 16; ++n) {
    for (double z : {0.25, 3.5, 7.8}) {
      const double left = one_sided_derivative(kind, order, n, z, -1);
      const double right = one_sided_derivative(kind, order, n, z, +1);
      if (std::abs(left - right) > tolerance) {
        return false;
      }
    }
  }
  return true;
}

TEST_CASE("interpolantsAreContinuous", "[interpolant]") {
  for (Interpolant kind : kAll) {
    CHECK(continuous_across_lattice_lines(kind, 0, 1e-3));
  }
}

TEST_CASE("cubicAndQuinticAreC1AndLinearIsNot", "[interpolant]") {
  CHECK(continuous_across_lattice_lines(Interpolant::kCubic, 1, 1e-2));
  CHECK(continuous_across_lattice_lines(Interpolant::kQuintic, 1, 1e-2));
  // Bilinear filtering has a kink at lattice lines: the check must be able to fail.
  CHECK_FALSE(continuous_across_lattice_lines(Interpolant::kLinear, 1, 1e-2));
}

TEST_CASE("quinticIsC2AndCubicIsNot", "[interpolant]") {
  CHECK(continuous_across_lattice_lines(Interpolant::kQuintic, 2, 0.1));
  CHECK_FALSE(continuous_across_lattice_lines(Interpolant::kCubic, 2, 0.1));
}

TEST_CASE("fadeCurvesMeetTheirEndConditions", "[interpolant]") {
  for (Interpolant kind : kAll) {
    CHECK(fade(kind, 0.0) == 0.0);
    CHECK(fade(kind, 1.0) == 1.0);
    CHECK(fade(kind, 0.5) == Approx(0.5));
    for (double t = 0; t < 1; t += 0.01) {
      CHECK(fade(kind, t) >= 0.0);
      CHECK(fade(kind, t) <= 1.0);
    }
  }
}

TEST_CASE("latticeSamplingIsSafeFarFromTheOrigin", "[interpolant]") {
  // The wrap keeps integer conversions in range however large the coordinate.
  const NoiseLattice& l = lattice16();
  for (float p : {1e8f, -1e8f, 3e38f, -3e38f, 16.0f, -1e-30f}) {
    const float s = sample_lattice<float>(l, Interpolant::kQuintic, p, -p);
    CHECK(std::isfinite(s));
    CHECK(s >= l.min_value);
    CHECK(s <= l.max_value);
  }
}

}  // namespace
}  // namespace relief
