// mesh_drawn_extent (core/sun_horizons.h) against points drawn inside the mesh's triangles: each
// point's Chebyshev distance in the sun's frame within [nearest, farthest], its height at least
// lowest; triangles around the camera, long and thin ones, a sun at 37 degrees of azimuth.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "core/sun_horizons.h"
#include "tests/support/hashed_draws.h"

namespace relief {
namespace {

TEST_CASE("aMeshsDrawnExtentHoldsEveryPointOfItsTriangles", "[shadows][geomipmap]") {
  ShadowPlan plan;
  plan.axis_x = std::cos(37.0 * M_PI / 180.0);
  plan.axis_z = std::sin(37.0 * M_PI / 180.0);
  test::HashedDraws draws(37);
  std::vector<float> dx, dz, height;
  std::vector<std::uint32_t> indices;
  for (int t = 0; t < 300; ++t) {
    // A third of them around the camera (the origin), the others up to 5000 away, some long.
    const double reach = t % 3 == 0 ? 30.0 : 5000.0, size = t % 7 == 0 ? 2000.0 : 40.0;
    const double cx = draws.uniform(-reach, reach), cz = draws.uniform(-reach, reach);
    for (int i = 0; i < 3; ++i) {
      indices.push_back(std::uint32_t(dx.size()));
      dx.push_back(float(cx + draws.uniform(-size, size)));
      dz.push_back(float(cz + draws.uniform(-size, size)));
      height.push_back(float(draws.uniform(-500.0, 500.0)));
    }
  }
  const std::size_t triangles = indices.size() / 3;
  for (const auto& [first, end] : {std::pair<std::size_t, std::size_t>{0, triangles},
                                   std::pair<std::size_t, std::size_t>{100, 101}}) {
    const DrawnExtent e = mesh_drawn_extent<float>(plan, indices, first, end, dx, dz, height);
    REQUIRE(e.nearest <= e.farthest);
    double nearest = HUGE_VAL, farthest = 0, lowest = HUGE_VAL;
    for (std::size_t t = first; t < end; ++t) {
      for (int k = 0; k < 200; ++k) {
        double a = draws.uniform(0.0, 1.0), b = draws.uniform(0.0, 1.0);
        if (a + b > 1.0) {
          a = 1.0 - a, b = 1.0 - b;
        }
        const double w[3] = {1.0 - a - b, a, b};
        double x = 0, z = 0, h = 0;
        for (int i = 0; i < 3; ++i) {
          const std::uint32_t v = indices[3 * t + std::size_t(i)];
          x += w[i] * dx[v], z += w[i] * dz[v], h += w[i] * height[v];
        }
        const double u = x * plan.axis_x + z * plan.axis_z, s = z * plan.axis_x - x * plan.axis_z;
        const double chebyshev = std::max(std::abs(u), std::abs(s));
        nearest = std::min(nearest, chebyshev);
        farthest = std::max(farthest, chebyshev);
        lowest = std::min(lowest, h);
        REQUIRE(chebyshev >= e.nearest);
        REQUIRE(chebyshev <= e.farthest);
        REQUIRE(h >= e.lowest - 1e-9 * std::abs(h));
      }
    }
    // Not vacuous: the bounds lie near what the points reach.
    CHECK(e.nearest > nearest - 4100.0);
    CHECK(e.farthest < 2.0 * farthest + 4100.0);
  }
  // No triangle: the empty extent.
  const DrawnExtent none = mesh_drawn_extent<float>(plan, indices, 5, 5, dx, dz, height);
  CHECK(none.nearest == HUGE_VAL);
  CHECK(none.farthest == 0.0);
}

}  // namespace
}  // namespace relief
