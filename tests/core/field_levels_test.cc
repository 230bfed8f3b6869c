// A height field's levels of detail (core/height_sketch.h, build_field_levels and add_sketch with
// nu): the levels against the test's own filter, their alignment (a ramp stays on level 0's
// samples), the blend against a direct evaluation, and the simd kernel bit-identical on every
// target.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "core/height_sketch.h"
#include "simd/sketch.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

HeightFieldSettings field_settings() {
  HeightFieldSettings s;
  s.image = "test";
  s.extent = {-500.0, -300.0, 700.0, 900.0};
  s.height = {0.0, 1.0};
  return s;
}

// The test's own reduce: every level's value i, j is the 5 x 5 binomial weighted sum of the
// level below around 2i, 2j (clamped to the edge), divided by 256, in double.
std::vector<std::vector<double>> oracle_levels(const std::vector<double>& level0, int w, int h,
                                               std::vector<std::pair<int, int>>& sides) {
  static constexpr double kBinomial[5] = {1, 4, 6, 4, 1};
  std::vector<std::vector<double>> levels = {level0};
  sides = {{w, h}};
  while (true) {
    const auto [cw, ch] = sides.back();
    const int nw = cw / 2 + 1, nh = ch / 2 + 1;
    if (nw >= cw && nh >= ch) {
      break;
    }
    const std::vector<double>& from = levels.back();
    std::vector<double> next(std::size_t(nw) * std::size_t(nh));
    for (int j = 0; j < nh; ++j) {
      for (int i = 0; i < nw; ++i) {
        double sum = 0;
        for (int b = -2; b <= 2; ++b) {
          for (int a = -2; a <= 2; ++a) {
            const int x = std::clamp(2 * i + a, 0, cw - 1), z = std::clamp(2 * j + b, 0, ch - 1);
            sum += kBinomial[a + 2] * kBinomial[b + 2] * from[std::size_t(z * cw + x)];
          }
        }
        next[std::size_t(j * nw + i)] = sum / 256.0;
      }
    }
    levels.push_back(next);
    sides.push_back({nw, nh});
  }
  return levels;
}

TEST_CASE("fieldLevelsAreTheBinomialReduceOfTheLevelBelow", "[heightfield]") {
  constexpr int kW = 37, kH = 22;
  std::vector<float> values(kW * kH);
  test::TestRandom rng(8);
  for (float& v : values) {
    v = float(rng.uniform(-50.0, 900.0));
  }
  const HeightSketch field = make_height_field(field_settings(), kW, kH, values, true);
  std::vector<std::pair<int, int>> sides;
  const std::vector<std::vector<double>> expected =
      oracle_levels(std::vector<double>(values.begin(), values.end()), kW, kH, sides);
  REQUIRE(field.levels() == int(expected.size()));
  CHECK(field.levels() == 7);  // 37 x 22, 19 x 12, 10 x 7, 6 x 4, 4 x 3, 3 x 2, 2 x 2
  CHECK(field.heights.size() == field_levels_samples(kW, kH));
  for (int l = 0; l < field.levels(); ++l) {
    INFO("level " << l);
    REQUIRE(field.level_width[std::size_t(l)] == sides[std::size_t(l)].first);
    REQUIRE(field.level_height[std::size_t(l)] == sides[std::size_t(l)].second);
    const std::vector<double>& want = expected[std::size_t(l)];
    for (std::size_t k = 0; k < want.size(); ++k) {
      const float got = field.heights[field.level_offset[std::size_t(l)] + k];
      CHECK(std::abs(double(got) - want[k]) <= 1e-6 * 900.0);
      // A convex filter: within level 0's extremes.
      CHECK(got >= field.min_height);
      CHECK(got <= field.max_height);
    }
  }
  // Degenerate sides: 2 x 2 has no coarser level (levels of detail then read level 0 only),
  // 3 x 2 one (2 x 2), 2 x 9 shrinks along z alone (2 x 5, 2 x 3, 2 x 2).
  for (const auto& [w, h, levels] :
       {std::tuple{2, 2, 1}, std::tuple{3, 2, 2}, std::tuple{2, 9, 4}}) {
    const std::vector<float> small(std::size_t(w * h), 0.5f);
    const HeightSketch f = make_height_field(field_settings(), w, h, small, true);
    INFO(w << " x " << h);
    CHECK(f.levels() == levels);
    CHECK(f.heights.size() == field_levels_samples(w, h));
    CHECK(std::all_of(f.heights.begin(), f.heights.end(), [](float v) { return v == 0.5f; }));
  }
  // Level 0 is the samples, the blocks and extremes are level 0's.
  CHECK(std::equal(values.begin(), values.end(), field.heights.begin()));
  const HeightSketch sketch = make_height_field(field_settings(), kW, kH, values);
  CHECK(sketch.levels() == 1);
  CHECK(sketch.heights.size() == std::size_t(kW * kH));
}

TEST_CASE("fieldLevelTexelsSitOnLevelZerosEveryTwoToTheL", "[heightfield]") {
  // The binomial filter keeps a linear ramp, so away from the edges level l's texel i holds
  // level 0's ramp at texel 2^l i: the alignment behind level_scale = 2^-l.
  constexpr int kW = 129, kH = 65;
  std::vector<float> ramp(kW * kH);
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      ramp[std::size_t(j * kW + i)] = float(3 * i - 2 * j);
    }
  }
  const HeightSketch field = make_height_field(field_settings(), kW, kH, ramp, true);
  int checked = 0;
  for (int l = 1; l < field.levels(); ++l) {
    const int w = field.level_width[std::size_t(l)], h = field.level_height[std::size_t(l)];
    // Level l's texel reads level 0 within 2^(l+1) - 2 texels of 2^l i: inside, no clamp.
    const int reach = (2 << l) - 2;
    const auto inside = [&](int i, int side) {
      return (i << l) - reach >= 0 && (i << l) + reach < side;
    };
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        if (!inside(i, kW) || !inside(j, kH)) {
          continue;
        }
        const float got = field.heights[field.level_offset[std::size_t(l)] +
                                        std::size_t(j) * std::size_t(w) + std::size_t(i)];
        INFO("level " << l << " texel " << i << ", " << j);
        CHECK(got == float(3 * (i << l) - 2 * (j << l)));
        ++checked;
      }
    }
  }
  CHECK(checked > 1000);
}

TEST_CASE("fieldLevelOfDetailBlendsTwoLevelsAndSimdMatchesOnEveryTarget", "[heightfield][simd]") {
  constexpr int kW = 70, kH = 45;
  std::vector<float> values(kW * kH);
  test::TestRandom rng(12);
  for (float& v : values) {
    v = float(rng.uniform(0.0, 500.0));
  }
  const HeightFieldSettings s = field_settings();
  const HeightSketch field = make_height_field(s, kW, kH, values, true);
  const SketchPlan plan = make_sketch_plan(s, field, 33.25, -120.5);
  const SketchParams<float> p = make_sketch_params<float>(plan, &field);
  const SketchParams<double> pd = make_sketch_params<double>(plan, &field);
  REQUIRE(p.levels == field.levels());
  constexpr std::size_t kCount = 517;
  std::vector<float> dx(kCount), dz(kCount), nu(kCount), base(kCount);
  std::vector<std::uint8_t> mask(kCount);
  for (std::size_t k = 0; k < kCount; ++k) {
    dx[k] = float(rng.uniform(-700.0, 800.0));
    dz[k] = float(rng.uniform(-500.0, 1200.0));
    // Levels below 0 and above the top clamp; whole and fractional levels.
    nu[k] = k % 7 == 0 ? float(k % 3) * 9.0f - 3.0f : float(rng.uniform(1.0, p.levels));
    base[k] = float(k) * 0.5f - 30.0f;
    mask[k] = static_cast<std::uint8_t>(k % 5 != 1);
  }
  std::vector<float> reference = base;
  add_sketch<float>(p, field.heights, IndexRange{0, kCount}, dx, dz, nu, {}, reference);
  // The blend against sample_field_level directly, in double: lambda = levels - nu.
  for (std::size_t k = 0; k < kCount; ++k) {
    const double lambda = std::clamp(double(p.levels) - double(nu[k]), 0.0, double(p.levels - 1));
    const int a = int(std::floor(lambda)), b = std::min(a + 1, p.levels - 1);
    const double sx = pd.offset_x + double(dx[k]) * pd.inv_cell_x;
    const double sz = pd.offset_z + double(dz[k]) * pd.inv_cell_z;
    const double fine = sample_field_level<double>(pd, field.heights, a, sx, sz);
    const double coarse = sample_field_level<double>(pd, field.heights, b, sx, sz);
    const double want = double(base[k]) + fine + (lambda - a) * (coarse - fine);
    INFO("k " << k << " nu " << nu[k]);
    CHECK(std::abs(double(reference[k]) - want) <= 1e-3);
  }
  const EachTarget targets;
  for (const std::span<const std::uint8_t> m :
       {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(mask)}) {
    for (const IndexRange range : {IndexRange{0, kCount}, IndexRange{5, kCount - 3}}) {
      std::vector<float> expected = base;
      add_sketch<float>(p, field.heights, range, dx, dz, nu, m, expected);
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<float> got = base;
        simd::add_sketch(p, field.heights, range, dx, dz, nu, m, got);
        INFO(target << ", range " << range.begin << ".." << range.end << ", mask " << m.size());
        CHECK(test::same_bits(got, expected));
      }
    }
  }
  INFO("targets compiled in but not run here: " << targets.skipped());
}

}  // namespace
}  // namespace relief
