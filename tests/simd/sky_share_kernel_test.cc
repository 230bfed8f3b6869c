// Sky light's per-pixel Highway kernel (simd/sky_share.h) against the scalar
// sky_visibility<float> (core/sky_horizons.h) on every target this CPU runs: rows of every
// awkward width (tests/simd/kernel_ranges.h), a third of the pixels uncovered, points in every
// level, in the blend bands and past the coarsest level: the shares and the work counters bit
// for bit, and no uncovered pixel or pixel past the row written; also for a cache of some of
// the levels only, as a frame builds.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/sky_horizons.h"
#include "core/sun_horizons.h"
#include "pipeline/scene_resources.h"
#include "simd/sky_share.h"
#include "simd/targets.h"
#include "tests/oracles/whole_frame.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/hashed_draws.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

bool same_sky_work(const SkyWork& a, const SkyWork& b) {
  return a.pixels == b.pixels && a.open == b.open && a.outside == b.outside;
}

TEST_CASE("theSkyShareKernelIsTheScalarStepOnEveryTarget", "[simd][sky]") {
  // Sky light alone: the cache without the sun's values, as such a frame builds it.
  const Scene scene = resolve_scene(
      "sunset", {"viewport.width=320", "viewport.height=256", "lighting.shadows=false"});
  const SceneResources resources = load_scene_resources(scene);
  const FramePlan frame = make_frame_plan(scene, resources.terrain_values());
  const ShadowPlan plan = make_shadow_plan(scene, frame);
  REQUIRE(plan.sky);
  REQUIRE(plan.levels > 6);
  test::HashedDraws draws(9);
  const auto unit = [&] { return draws.uniform(0.0, 1.0); };
  // Points at every scale of the levels, from the finest square to past the coarsest.
  const auto point = [&](float& dx, float& dz) {
    const double reach =
        plan.spacing[0] * std::exp2(unit() * (plan.levels + 1)) * plan.resolution * 0.5;
    const double angle = unit() * 6.283185307179586;
    dx = float(reach * std::cos(angle));
    dz = float(reach * std::sin(angle));
  };
  const EachTarget targets;
  SkyWork reached;
  std::size_t shaded = 0;  // points whose share is neither 1 nor 0: the interpolation's
  for (const auto& [first, end] : {std::pair{0, plan.levels}, std::pair{2, plan.levels - 3}}) {
    const SunHorizonCache<float> cache =
        build_horizon_cache<float>(plan, frame, resources, first, end);
    REQUIRE(cache.tangent.empty());
    ShadowParams<float> params = make_shadow_params<float>(plan);
    params.first_level = first;
    params.end_level = end;
    for (const std::size_t width : test::awkward_lengths()) {
      const int w = int(width), rows = 2, stride = 64;
      const std::size_t pixels = std::size_t(rows) * stride;
      std::vector<std::uint32_t> covered(pixels, 0xffffffffu);
      std::vector<float> dx(pixels, 0.0f), dz(pixels, 0.0f);
      for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < w; ++i) {
          const std::size_t k = std::size_t(j) * stride + i;
          covered[k] = unit() < 1.0 / 3.0 ? 0xffffffffu : std::uint32_t(k);
          point(dx[k], dz[k]);
        }
      }
      std::vector<float> expected(pixels, test::sentinel<float>());
      SkyWork scalar;
      for (std::size_t k = 0; k < pixels; ++k) {
        if (covered[k] != 0xffffffffu && int(k % stride) < w) {
          expected[k] = sky_visibility<float>(params, cache, dx[k], dz[k], scalar);
          shaded += expected[k] > 0.0f && expected[k] < 1.0f;
        }
      }
      reached += scalar;
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<float> got(pixels, test::sentinel<float>());
        SkyWork vector;
        simd::sky_shares(params, cache, covered, dx, dz, w, rows, stride, got, vector);
        INFO(target << ", levels [" << first << ", " << end << "), width " << w);
        REQUIRE(test::same_bits<float>(got, expected));
        REQUIRE(same_sky_work(vector, scalar));
      }
    }
  }
  CHECK(reached.outside > 0);
  CHECK(reached.pixels > reached.outside);
  CHECK(shaded > 0);
}

}  // namespace
}  // namespace relief
