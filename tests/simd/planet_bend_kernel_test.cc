// A planet's bend as Highway kernels (simd/planet_bend.h) over ranges of every awkward length
// (tests/simd/kernel_ranges.h) on every target this CPU runs: every value inside the range is
// core/planet_bend.h's bit for bit (the vertices' bent positions and drops, the normals
// rotated in place), and no element outside the range is written.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/planet_bend.h"
#include "core/planet_plan.h"
#include "simd/planet_bend.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr std::size_t kBendCapacity = 5 + 53 + test::kGuardElements;

// The planet preset's sphere seen from 1,000 km up.
PlanetParams<float> bend_params() {
  PlanetParams<float> p;
  p.enabled = 1;
  p.visible = 1;
  p.radius = 2.0e6f;
  p.inv_radius = float(1.0 / 2.0e6);
  p.center_distance = float(2.0e6 + 1.0e6);
  return p;
}

// Arc offsets from the nadir (exactly 0: theta 0, the sinc's limit and the undefined
// direction) through tiny ones (sin x = x) to 14 radii (theta 14 radians, inside
// sin_cos_det's domain |x| <= 64: many quadrants), heights about the datum, holes among the
// valid flags.
struct BendInputs {
  std::vector<float> dx, dz, height, nx, ny, nz;
  std::vector<std::uint8_t> valid;

  BendInputs() {
    test::TestRandom random(83);
    for (std::size_t k = 0; k < kBendCapacity; ++k) {
      const double scale = k % 4 == 0 ? 1e-3 : (k % 4 == 1 ? 2e4 : (k % 4 == 2 ? 2e6 : 2e7));
      dx.push_back(k % 7 == 3 ? 0.0f : float(random.uniform(-1, 1) * scale));
      dz.push_back(k % 7 == 3 ? 0.0f : float(random.uniform(-1, 1) * scale));
      height.push_back(float(random.uniform(-3000, 9000)));
      nx.push_back(float(random.uniform(-1, 1)));
      ny.push_back(float(random.uniform(0, 1)));
      nz.push_back(float(random.uniform(-1, 1)));
      valid.push_back(random.uniform(0, 1) < 0.8 ? 1 : 0);
    }
  }
};

// The bend's four outputs, every element a sentinel that a write would change.
std::array<std::vector<float>, 4> sentinel_outputs() {
  std::array<std::vector<float>, 4> out;
  out.fill(std::vector<float>(kBendCapacity, test::sentinel<float>()));
  return out;
}

TEST_CASE("simdPlanetBendAtAwkwardLengthsIsTheScalarBendAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  const PlanetParams<float> p = bend_params();
  const BendInputs in;
  for (const std::size_t start : test::kRangeStarts) {
    for (const std::size_t length : test::awkward_lengths()) {
      const IndexRange range{start, start + length};
      std::array<std::vector<float>, 4> expected = sentinel_outputs();
      bend_vertices<float>(p, range, in.dx, in.dz, in.height, in.valid,
                           {expected[0], expected[1], expected[2], expected[3]});
      INFO("start " << start << ", length " << length);
      REQUIRE(test::untouched_outside(expected[3], range.begin, range.end));
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::array<std::vector<float>, 4> got = sentinel_outputs();
        simd::bend_vertices(p, range, in.dx, in.dz, in.height, in.valid,
                            {got[0], got[1], got[2], got[3]});
        INFO(target);
        for (int c = 0; c < 4; ++c) {
          CHECK(test::same_bits(got[c], expected[c]));
        }
      }
    }
  }
}

TEST_CASE("simdPlanetNormalsAtAwkwardLengthsAreTheScalarRotationAndWriteOnlyTheirRange", "[simd]") {
  const EachTarget targets;
  const PlanetParams<float> p = bend_params();
  const BendInputs in;
  for (const std::size_t start : test::kRangeStarts) {
    for (const std::size_t length : test::awkward_lengths()) {
      const IndexRange range{start, start + length};
      std::vector<float> expected[3] = {in.nx, in.ny, in.nz};
      bend_normals<float>(p, range, in.dx, in.dz, in.valid, expected[0], expected[1], expected[2]);
      INFO("start " << start << ", length " << length);
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<float> got[3] = {in.nx, in.ny, in.nz};
        simd::bend_normals(p, range, in.dx, in.dz, in.valid, got[0], got[1], got[2]);
        INFO(target);
        for (int c = 0; c < 3; ++c) {
          // Outside the range the inputs stay: the scalar code leaves them too.
          CHECK(test::same_bits(got[c], expected[c]));
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
