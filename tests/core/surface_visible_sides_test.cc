// Stage 4's visible sides (core/surface.h): at a silhouette a vertex's difference no longer
// reaches into the slope hidden behind it. Hand-built grids, the eye at the origin, checked
// against normals the test forms itself from the vertices (central or one-sided differences),
// and the Highway kernel against the reference on every target.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "core/limits.h"
#include "core/surface.h"
#include "simd/surface.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// A grid of width x height vertices in front of the eye: column i at x = i - width / 2, row j
// at z = row_z(j) (by default -(10 + j); rows run away from the eye), camera-relative height
// h(i, j).
template <class Real>
struct SyntheticGrid {
  int width = 0, height = 0;
  int pitch = 0;  // rows padded to 16 vertices, as GridLayout pads them for the widest vector
  std::vector<Real> dx, dz, h;
  std::vector<std::uint8_t> valid;
  std::vector<Real> nx, ny, nz, slope, water;

  SyntheticGrid(
      int w, int rows, const std::function<double(int, int)>& height_at,
      const std::function<double(int)>& row_z = [](int j) { return -(10.0 + j); })
      : width(w), height(rows), pitch((w + 15) / 16 * 16) {
    const std::size_t n = std::size_t(pitch) * std::size_t(rows);
    for (auto* v : {&dx, &dz, &h, &nx, &ny, &nz, &slope, &water}) {
      v->assign(n, Real(0));
    }
    valid.assign(n, 0);
    for (int j = 0; j < rows; ++j) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = index(i, j);
        valid[k] = 1;
        dx[k] = Real(i - w / 2);
        dz[k] = Real(row_z(j));
        h[k] = Real(height_at(i, j));
      }
    }
  }
  std::size_t index(int i, int j) const { return std::size_t(j) * std::size_t(pitch) + i; }

  SurfaceParams<Real> params() const {
    SurfaceParams<Real> p;
    p.width = width;
    p.height = height;
    p.pitch = pitch;
    p.water_enabled = 0;
    p.min_sine_sq = Real(limits::kMinTangentSine * limits::kMinTangentSine);
    p.max_slope = Real(limits::kMaxSlope);
    p.inv_silhouette_facing = Real(1.0 / limits::kSilhouetteFacing);
    p.hidden_side_weight = Real(limits::kHiddenSideWeight);
    return p;
  }
  SurfaceInputs<Real> inputs() const { return {dx, dz, h, valid, {}}; }
  SurfaceSpans<Real> outputs() { return {nx, ny, nz, slope, water}; }
  void run() { surface_pass<Real>(params(), RowRange{0, height}, inputs(), outputs()); }

  // The unit upward normal of the plane spanned by tangents a (along i) and b (along j),
  // formed here in double.
  static std::array<double, 3> plane_normal(const std::array<double, 3>& a,
                                            const std::array<double, 3>& b) {
    // (x, h, z) components; upward normal of a x b oriented to positive h.
    double n[3] = {-(a[1] * b[2] - a[2] * b[1]), a[0] * b[2] - a[2] * b[0],
                   -(a[0] * b[1] - a[1] * b[0])};
    const double sign = n[1] > 0 ? 1 : -1;
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return {n[0] * sign / length, n[1] * sign / length, n[2] * sign / length};
  }
  std::array<double, 3> position(int i, int j) const {
    const std::size_t k = index(i, j);
    return {double(dx[k]), double(h[k]), double(dz[k])};
  }
  static std::array<double, 3> minus(const std::array<double, 3>& p,
                                     const std::array<double, 3>& q) {
    return {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
  }
  // The plain central-difference normal at an interior vertex.
  std::array<double, 3> central_normal(int i, int j) const {
    return plane_normal(minus(position(i + 1, j), position(i - 1, j)),
                        minus(position(i, j + 1), position(i, j - 1)));
  }
  // The normal with the j axis's difference one-sided towards the eye (rows j - 1 to j).
  std::array<double, 3> near_side_normal(int i, int j) const {
    return plane_normal(minus(position(i + 1, j), position(i - 1, j)),
                        minus(position(i, j), position(i, j - 1)));
  }
  // The normal with the j axis's difference w_near (p(j) - p(j - 1)) + w_far (p(j + 1) - p(j)).
  std::array<double, 3> weighted_normal(int i, int j, double w_near, double w_far) const {
    const auto near = minus(position(i, j), position(i, j - 1));
    const auto far = minus(position(i, j + 1), position(i, j));
    return plane_normal(minus(position(i + 1, j), position(i - 1, j)),
                        {w_near * near[0] + w_far * far[0], w_near * near[1] + w_far * far[1],
                         w_near * near[2] + w_far * far[2]});
  }
  std::array<double, 3> normal(int i, int j) const {
    const std::size_t k = index(i, j);
    return {double(nx[k]), double(ny[k]), double(nz[k])};
  }
};

// A ridge along x: rows at heights near, crest, far (the eye at height 0).
double ridge(int j, double far) {
  return j == 0 ? -5.0 : (j == 1 ? -4.0 : far);
}

double angle(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::acos(std::clamp(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], -1.0, 1.0));
}

// The crest's normal when the far side is hidden: the near half of the difference in full, the
// far half's share kHiddenSideWeight.
template <class Real>
std::array<double, 3> near_side_with_hidden_share(const SyntheticGrid<Real>& grid) {
  return grid.weighted_normal(1, 1, 1.0, limits::kHiddenSideWeight);
}

TEMPLATE_TEST_CASE("aCrestSeenFromTheFrontIsShadedAsItsVisibleSide", "[surface]", float, double) {
  // From the eye the crest (z = -11, h = -4) is seen along a ray falling 4/11; the far row
  // (z = -12, h = -8) lies below that ray, hidden behind the crest.
  SyntheticGrid<TestType> grid(3, 3, [](int, int j) { return ridge(j, -8.0); });
  grid.run();
  const auto central = grid.central_normal(1, 1);
  const auto visible = grid.near_side_normal(1, 1);
  // The central difference reaches over the crest: its normal faces away from the eye
  // (+z points towards it), which is what drew dark lines along silhouettes.
  REQUIRE(central[2] < 0);
  REQUIRE(visible[2] > 0.5);
  const auto got = grid.normal(1, 1);
  INFO("from the visible side's normal " << angle(got, visible) << " rad, from the central "
                                         << angle(got, central));
  const auto expected = near_side_with_hidden_share(grid);
  for (int c = 0; c < 3; ++c) {
    CHECK(got[c] == Approx(expected[c]).margin(1e-6));
  }
  CHECK(angle(got, visible) < 0.1);  // the hidden share leans it by little
  CHECK(angle(got, central) > 0.3);
}

TEMPLATE_TEST_CASE("sidesThatFaceTheEyeKeepTheCentralDifference", "[surface]", float, double) {
  // Gentle bumps seen from 100 units above: every side faces the eye far more than
  // kSilhouetteFacing, so every interior normal is the central difference's.
  SyntheticGrid<TestType> grid(9, 9, [](int i, int j) {
    return -100.0 + 0.7 * std::sin(1.3 * i + 0.4 * j) + 0.5 * std::cos(0.9 * j - 0.2 * i);
  });
  grid.run();
  for (int j = 1; j + 1 < grid.height; ++j) {
    for (int i = 1; i + 1 < grid.width; ++i) {
      const auto expected = grid.central_normal(i, j);
      const auto got = grid.normal(i, j);
      INFO("vertex " << i << ", " << j);
      for (int c = 0; c < 3; ++c) {
        CHECK(got[c] == Approx(expected[c]).margin(std::is_same_v<TestType, float> ? 1e-6 : 1e-12));
      }
    }
  }
}

TEMPLATE_TEST_CASE("theNormalTurnsContinuouslyAsTheFarSideSinksOutOfSight", "[surface]", float,
                   double) {
  // The far row lowered from above the crest (every side seen) to well below the crest's ray
  // (hidden) in small steps: the crest's normal goes from the central difference's to the
  // near side's without a jump. The far row lies 2 units beyond the crest and the near one 1
  // before it, so the two halves of the difference differ in size (as where the rows' spacing
  // grows with distance): halves scaled apart before their weighted sum would jump where a
  // weight reaches 1.
  const int steps = 4000;
  const double top = -3.0, bottom = -8.0, step = (top - bottom) / steps;
  const auto row_z = [](int j) { return j == 0 ? -10.0 : (j == 1 ? -11.0 : -13.0); };
  const auto crest_normal = [&](double far, bool central) {
    SyntheticGrid<TestType> grid(
        3, 3, [far](int, int j) { return ridge(j, far); }, row_z);
    grid.run();
    return std::pair{grid.normal(1, 1),
                     central ? grid.central_normal(1, 1) : near_side_with_hidden_share(grid)};
  };
  const auto [first, central] = crest_normal(top, true);
  const auto [last, visible] = crest_normal(bottom, false);
  for (int c = 0; c < 3; ++c) {
    CHECK(first[c] == Approx(central[c]).margin(1e-6));
  }
  for (int c = 0; c < 3; ++c) {
    CHECK(last[c] == Approx(visible[c]).margin(1e-6));
  }
  // Where the far side grazes the crest's ray (far = -4 * 13 / 11) the two differences differ
  // by `jump`: what a switch from one to the other would turn the normal by at once.
  const auto grazing_central = crest_normal(-52.0 / 11.0, true).second;
  const auto grazing_visible = crest_normal(-52.0 / 11.0, false).second;
  const double jump = angle(grazing_central, grazing_visible);
  REQUIRE(jump > 0.3);
  double largest_change = 0;
  std::array<double, 3> previous = first;
  for (int s = 1; s <= steps; ++s) {
    const auto n = crest_normal(top - s * step, true).first;
    largest_change =
        std::max(largest_change, std::sqrt((n[0] - previous[0]) * (n[0] - previous[0]) +
                                           (n[1] - previous[1]) * (n[1] - previous[1]) +
                                           (n[2] - previous[2]) * (n[2] - previous[2])));
    previous = n;
  }
  // Each step lowers the far row by about 1e-3: a continuous normal turns by about that much
  // (its derivative here is of order 1); a switch between the two differences would turn it
  // by `jump` in one step.
  INFO("jump " << jump << " rad; largest change of one step " << largest_change);
  CHECK(largest_change < 0.01);
}

// Rough terrain close below the eye, 41 x 33 vertices with a tenth of them holes (invalid, as
// stage 3 leaves them): many sides face the eye at grazing angles or not at all, and every
// neighbour case of the weighting occurs. Positions times `scale`.
template <class Real>
SyntheticGrid<Real> rough_grid(double scale = 1.0) {
  test::TestRandom random(23);
  std::vector<double> bumps(41 * 33);
  for (double& b : bumps) {
    b = random.uniform(-3, 3);
  }
  SyntheticGrid<Real> g(41, 33, [&](int i, int j) { return -4.0 + bumps[j * 41 + i]; });
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const std::size_t k = g.index(i, j);
      g.valid[k] = random.uniform(0, 1) < 0.1 ? 0 : 1;
      g.dx[k] = g.dx[k] * Real(scale);
      g.dz[k] = g.dz[k] * Real(scale);
      g.h[k] = g.h[k] * Real(scale);
    }
  }
  return g;
}

TEST_CASE("simdVisibleSidesAreBitIdenticalToTheReferenceOnEveryTarget", "[simd][surface]") {
  const auto grid = [] { return rough_grid<float>(); };
  SyntheticGrid<float> expected = grid();
  expected.run();
  // Independently of the code: the vertices whose normal is not the central difference's
  // (the weighting ran there), so that the comparison below covers it.
  int weighed = 0;
  for (int j = 1; j + 1 < expected.height; ++j) {
    for (int i = 1; i + 1 < expected.width; ++i) {
      bool all_valid = true;
      for (const auto& [ii, jj] :
           {std::pair{i, j}, {i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}}) {
        all_valid = all_valid && expected.valid[expected.index(ii, jj)] != 0;
      }
      if (!all_valid) {
        continue;
      }
      const auto central = expected.central_normal(i, j), got = expected.normal(i, j);
      weighed += std::abs(central[0] - got[0]) + std::abs(central[1] - got[1]) +
                     std::abs(central[2] - got[2]) >
                 1e-3;
    }
  }
  CHECK(weighed > 100);
  const EachTarget targets;
  for (const std::string& target : targets.runnable()) {
    simd::force_target(target);
    SyntheticGrid<float> got = grid();
    simd::surface_pass(got.params(), RowRange{0, got.height}, got.inputs(), got.outputs());
    INFO(target);
    CHECK(test::same_bits(got.nx, expected.nx));
    CHECK(test::same_bits(got.ny, expected.ny));
    CHECK(test::same_bits(got.nz, expected.nz));
    CHECK(test::same_bits(got.slope, expected.slope));
  }
}

TEMPLATE_TEST_CASE("visibleSidesGiveTheSameNormalsAtAnyPowerOfTwoScale", "[surface]", float,
                   double) {
  // Every difference is scaled to a largest component of 1 before it is multiplied, so a
  // scene scaled by a power of two (exact in binary) down to spacings of 1e-18 or up to 1e18
  // gives the same bits: no product underflows or overflows on the way.
  SyntheticGrid<TestType> unit = rough_grid<TestType>();
  unit.run();
  for (const double scale : {0x1p-60, 0x1p-20, 0x1p20, 0x1p60}) {
    SyntheticGrid<TestType> scaled = rough_grid<TestType>(scale);
    scaled.run();
    INFO("scale " << scale);
    CHECK(test::same_bits(scaled.nx, unit.nx));
    CHECK(test::same_bits(scaled.ny, unit.ny));
    CHECK(test::same_bits(scaled.nz, unit.nz));
    CHECK(test::same_bits(scaled.slope, unit.slope));
  }
}

TEMPLATE_TEST_CASE("degenerateSidesGiveAFiniteUpwardUnitNormal", "[surface]", float, double) {
  // A neighbour on top of the vertex (a side of length 0), the vertex at the eye (no ray), a
  // side straight down (a vertical patch, whose upward sign is a tie) and a side straight up:
  // the weights' undefined cosines must leave a finite unit normal with ny > 0.
  const std::vector<std::function<void(SyntheticGrid<TestType>&)>> cases = {
      [](SyntheticGrid<TestType>& g) {
        const std::size_t c = g.index(1, 1), n = g.index(1, 2);
        g.dx[n] = g.dx[c], g.dz[n] = g.dz[c], g.h[n] = g.h[c];
      },
      [](SyntheticGrid<TestType>& g) {
        const std::size_t c = g.index(1, 1);
        g.dx[c] = g.dz[c] = g.h[c] = TestType(0);
      },
      [](SyntheticGrid<TestType>& g) {
        const std::size_t c = g.index(1, 1), n = g.index(1, 2);
        g.dx[n] = g.dx[c], g.dz[n] = g.dz[c], g.h[n] = g.h[c] - TestType(50);
      },
      [](SyntheticGrid<TestType>& g) {
        const std::size_t c = g.index(1, 1), n = g.index(2, 1);
        g.dx[n] = g.dx[c], g.dz[n] = g.dz[c], g.h[n] = g.h[c] + TestType(50);
      },
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SyntheticGrid<TestType> grid(3, 3, [](int, int j) { return ridge(j, -8.0); });
    cases[k](grid);
    grid.run();
    const auto n = grid.normal(1, 1);
    INFO("case " << k << ": normal " << n[0] << ", " << n[1] << ", " << n[2]);
    CHECK(std::isfinite(n[0]));
    CHECK(std::isfinite(n[2]));
    CHECK(n[1] > 0);
    CHECK(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) == Approx(1.0).margin(1e-6));
    CHECK(std::isfinite(grid.slope[grid.index(1, 1)]));
  }
}

}  // namespace
}  // namespace relief
