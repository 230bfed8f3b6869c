// Stage 3's Highway kernels (simd/fbm.h, simd/sketch.h) over ranges of every awkward length
// (tests/simd/kernel_ranges.h) on every target this CPU runs: the heights inside the range are
// the scalar stage's (core/fbm.h, core/height_sketch.h) bit for bit, and no element outside the
// range is written. Whole frames and long ranges: tests/simd/simd_test.cc.
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_sketch.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "simd/fbm.h"
#include "simd/sketch.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Every buffer is this long: the largest start, the longest range and the guard.
constexpr std::size_t kCapacity = 5 + 53 + test::kGuardElements;

// Camera-relative points of a frame and their octave counts, and a mask that drops about a
// third of them (the culling stages' kEvaluate).
struct FractalPoints {
  std::vector<float> dx, dz, nu;
  std::vector<std::uint8_t> mask;
};

FractalPoints fractal_points(double reach, double nu_max, std::uint64_t seed) {
  test::TestRandom random(seed);
  FractalPoints p;
  for (std::size_t k = 0; k < kCapacity; ++k) {
    p.dx.push_back(float(random.uniform(-reach, reach)));
    p.dz.push_back(float(random.uniform(-reach, reach)));
    p.nu.push_back(float(random.uniform(0, nu_max)));
    p.mask.push_back(random.uniform(0, 1) < 0.67 ? 1 : 0);
  }
  return p;
}

TEST_CASE("simdFbmAtAwkwardLengthsIsTheScalarFbmAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  // The plain terrain, the warp, and fine octaves in the exact coordinate form
  // (core/octave_coordinates.h).
  for (const std::vector<std::string>& terrain : std::vector<std::vector<std::string>>{
           {}, {"terrain.warp.enabled=true"}, {"terrain.H=0.05", "terrain.last_octave=23"}}) {
    std::vector<std::string> overrides = {"grid.width=16", "grid.height=16"};
    overrides.insert(overrides.end(), terrain.begin(), terrain.end());
    const Scene scene = resolve_scene("default", overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    FbmParams<float> params = make_terrain_params<float>(plan).fbm;
    const FractalPoints p = fractal_points(3000.0, params.count, 41);
    const std::vector<std::uint8_t> all_valid(kCapacity, 1);
    choose_coordinate_forms(
        plan.terrain, octave_reach<float>(IndexRange{0, kCapacity}, p.dx, p.dz, p.nu, all_valid),
        params);
    for (const std::span<const std::uint8_t> mask :
         {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(p.mask)}) {
      for (const std::size_t start : test::kRangeStarts) {
        for (const std::size_t length : test::awkward_lengths()) {
          const IndexRange range{start, start + length};
          std::vector<float> expected(kCapacity, test::sentinel<float>());
          const FbmWork expected_work =
              evaluate_fbm<float>(params, lattice, range, p.dx, p.dz, p.nu, mask, expected);
          INFO((terrain.empty() ? std::string("plain") : terrain.front())
               << ", mask " << mask.size() << ", start " << start << ", length " << length);
          REQUIRE(test::untouched_outside(expected, range.begin, range.end));
          for (const std::string& target : targets.runnable()) {
            simd::force_target(target);
            std::vector<float> got(kCapacity, test::sentinel<float>());
            const FbmWork work =
                simd::evaluate_fbm(params, lattice, range, p.dx, p.dz, p.nu, mask, got);
            INFO(target);
            CHECK(test::same_bits(got, expected));
            CHECK(work.points == expected_work.points);
            CHECK(work.octaves == expected_work.octaves);
          }
        }
      }
    }
  }
}

TEST_CASE("simdSketchAtAwkwardLengthsIsTheScalarSketchAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  // A 9 x 7 sketch over [-100, 100] x [-50, 50], a camera near its corner: the points fall
  // inside, on the clamped border and far outside it.
  SketchSettings settings;
  settings.image = "test";
  settings.extent = {-100.0, -50.0, 100.0, 50.0};
  settings.height = {-200.0, 800.0};
  test::TestRandom random(43);
  std::vector<std::uint16_t> grey(9 * 7);
  for (std::uint16_t& g : grey) {
    g = static_cast<std::uint16_t>(random.uniform(0, 65535));
  }
  const HeightSketch sketch = make_height_sketch(settings, 9, 7, grey, 65535);
  const SketchParams<float> params =
      make_sketch_params<float>(make_sketch_plan(settings, sketch, 90.0, -40.0), &sketch);
  const FractalPoints p = fractal_points(250.0, 1.0, 47);
  // The fractal's heights the sketch is added to; the sentinel outside the range.
  std::vector<float> fractal(kCapacity);
  for (float& h : fractal) {
    h = float(random.uniform(-300, 300));
  }
  for (const std::span<const std::uint8_t> mask :
       {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(p.mask)}) {
    for (const std::size_t start : test::kRangeStarts) {
      for (const std::size_t length : test::awkward_lengths()) {
        const IndexRange range{start, start + length};
        std::vector<float> before(kCapacity, test::sentinel<float>());
        std::copy(fractal.begin() + std::ptrdiff_t(range.begin),
                  fractal.begin() + std::ptrdiff_t(range.end),
                  before.begin() + std::ptrdiff_t(range.begin));
        std::vector<float> expected = before;
        add_sketch<float>(params, sketch.heights, range, p.dx, p.dz, {}, mask, expected);
        INFO("mask " << mask.size() << ", start " << start << ", length " << length);
        REQUIRE(test::untouched_outside(expected, range.begin, range.end));
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          std::vector<float> got = before;
          simd::add_sketch(params, sketch.heights, range, p.dx, p.dz, {}, mask, got);
          INFO(target);
          CHECK(test::same_bits(got, expected));
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
