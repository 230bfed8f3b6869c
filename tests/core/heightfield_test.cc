// The height-map generators (core/heightfield/): deterministic from the seed; the
// displacements' statistics; Miller's claims about each method's interpolant, measured against
// the calculus they rest on (a crease makes the second difference shrink as the spacing h, a C1
// surface of bounded curvature as h^2); the interpolating methods pass through their control
// points; Perlin noise vanishes at its lattice points; smoothing keeps the mean.
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include <catch2/catch.hpp>

#include "core/heightfield/creases.h"
#include "core/heightfield/perlin_field.h"
#include "core/heightfield/smoothing.h"
#include "core/heightfield/subdivision.h"

namespace relief {
namespace {

constexpr Subdivision kMethods[] = {Subdivision::kTriangleEdge, Subdivision::kDiamondSquare,
                                    Subdivision::kSquareSquare};

// Miller's test case: a 4 x 4 periodic grid of control points at one level, one raised.
PeriodicGrid raised_point() {
  PeriodicGrid g(4);
  g.at(1, 1) = 1.0f;
  return g;
}

// The interpolant alone: no displacement at any level.
PeriodicGrid interpolant(Subdivision method, int levels) {
  return subdivide(raised_point(), {method, levels, 1.0, 0.8, 1, 0});
}

TEST_CASE("generatedMapsArePureFunctionsOfTheirSettings", "[heightfield]") {
  for (const Subdivision method : kMethods) {
    INFO(subdivision_name(method));
    const SubdivisionSettings s{method, 7, 100.0, 0.7, 42};
    const PeriodicGrid a = subdivide(PeriodicGrid(1), s);
    CHECK(a.side == 128);
    CHECK(subdivide(PeriodicGrid(1), s).heights == a.heights);
    SubdivisionSettings other = s;
    other.seed = 43;
    CHECK(subdivide(PeriodicGrid(1), other).heights != a.heights);
    for (const float h : a.heights) {
      REQUIRE(std::isfinite(h));
    }
  }
  const PerlinSettings p{256, 4, 10.0, 0.8, 5};
  CHECK(perlin_field(p).heights == perlin_field(p).heights);
}

TEST_CASE("displacementsHaveMeanZeroAndVarianceOne", "[heightfield]") {
  double sum = 0, squares = 0, fourth = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double g = subdivision_gaussian(9, Subdivision::kSquareSquare, 3, std::uint64_t(k));
    sum += g;
    squares += g * g;
    fourth += g * g * g * g;
  }
  const double mean = sum / n, variance = squares / n - mean * mean;
  // Standard errors: 1 / sqrt(n) = 0.0022 for the mean, sqrt(2 / n) = 0.0032 for the variance.
  CHECK(std::abs(mean) < 0.011);
  CHECK(std::abs(variance - 1.0) < 0.016);
  // Irwin-Hall with four terms: kurtosis 3 - 6/20 = 2.7 (a Gaussian's is 3).
  CHECK(fourth / n == Approx(2.7).epsilon(0.02));
}

TEST_CASE("squareSquareIsC1WhereTriangleEdgeAndDiamondSquareCrease", "[heightfield]") {
  // Halving the spacing: the largest second difference falls by 4 on a C1 surface of bounded
  // curvature (h^2), by only 2 across a slope discontinuity (h).
  for (const Subdivision method : kMethods) {
    const double coarse = largest_second_difference(interpolant(method, 6));
    const double fine = largest_second_difference(interpolant(method, 7));
    const double ratio = fine / coarse;
    INFO(subdivision_name(method) << ": " << coarse << " -> " << fine << " (" << ratio << ")");
    if (method == Subdivision::kSquareSquare) {
      CHECK(ratio == Approx(0.25).epsilon(0.05));
    } else if (method == Subdivision::kTriangleEdge) {
      CHECK(ratio == Approx(0.5).epsilon(0.05));
    } else {
      // Diamond-square falls slower still (0.65 here): besides its creases its interpolant
      // has points where the slope itself grows without bound (Miller: "very pointed towards
      // the peak"), where a second difference shrinks slower than h.
      CHECK(ratio > 0.5);
      CHECK(ratio < 1.0);
    }
  }
  // The creases lie along the coarse levels' lines: far above the mean there for the two
  // Miller found creasing, about the mean for square-square.
  for (const Subdivision method : kMethods) {
    const PeriodicGrid random_then_smooth = subdivide(PeriodicGrid(1), {method, 8, 1.0, 0.8, 3, 3});
    const double ratio = crease_ratio(random_then_smooth, 3);
    INFO(subdivision_name(method) << ": crease ratio " << ratio);
    if (method == Subdivision::kSquareSquare) {
      CHECK((ratio > 0.8 && ratio < 1.25));
    } else {
      CHECK(ratio > 3.0);
    }
  }
}

TEST_CASE("interpolatingMethodsPassThroughTheirControlPoints", "[heightfield]") {
  for (const Subdivision method : {Subdivision::kTriangleEdge, Subdivision::kDiamondSquare}) {
    const PeriodicGrid g = subdivide(raised_point(), {method, 5, 3.0, 0.8, 11});
    for (int z = 0; z < 4; ++z) {
      for (int x = 0; x < 4; ++x) {
        CHECK(g.at(32 * x, 32 * z) == raised_point().at(x, z));
      }
    }
  }
  // Square-square does not (Miller: "the control points deflect the surface but do not
  // normally lie on it"): the raised point's value is spread.
  const PeriodicGrid ss = interpolant(Subdivision::kSquareSquare, 5);
  const auto [low, high] = std::minmax_element(ss.heights.begin(), ss.heights.end());
  CHECK(*high < 0.9f);
  CHECK(*low >= 0.0f);
}

TEST_CASE("perlinNoiseVanishesAtItsLatticeAndSmoothingKeepsTheMean", "[heightfield]") {
  PerlinSettings one{128, 4, 1.0, 0.8, 2};
  one.max_octaves = 1;
  const PeriodicGrid g = perlin_field(one);
  for (int z = 0; z < 128; z += 32) {
    for (int x = 0; x < 128; x += 32) {
      CHECK(g.at(x, z) == 0.0f);
    }
  }
  PeriodicGrid map = subdivide(PeriodicGrid(1), {Subdivision::kDiamondSquare, 7, 50.0, 0.6, 4});
  const double before = std::accumulate(map.heights.begin(), map.heights.end(), 0.0);
  const double rough = largest_second_difference(map);
  smooth_height_map(map, 3);
  const double after = std::accumulate(map.heights.begin(), map.heights.end(), 0.0);
  CHECK(after / map.heights.size() == Approx(before / map.heights.size()).margin(1e-3));
  CHECK(largest_second_difference(map) < 0.5 * rough);
}

}  // namespace
}  // namespace relief
