// The cast shadows' per-pixel Highway kernel (simd/sun_share.h) against the scalar
// sun_visibility<float> (core/sun_visibility.h) on every target this CPU runs: rows of every
// awkward width (tests/simd/kernel_ranges.h), a third of the pixels uncovered, points in every
// level, in the blend bands, past the coarsest level and with the sun set, with the lit skip on
// and off: the shares and the work counters bit for bit, and no uncovered pixel or pixel past
// the row written; also for a cache of some of the levels only, as a frame builds.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/sun_horizons.h"
#include "core/sun_visibility.h"
#include "pipeline/scene_resources.h"
#include "simd/sun_share.h"
#include "simd/targets.h"
#include "tests/oracles/whole_frame.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/hashed_draws.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

bool same_work(const ShadowWork& a, const ShadowWork& b) {
  return a.pixels == b.pixels && a.lit == b.lit && a.evaluated == b.evaluated && a.dark == b.dark &&
         a.outside == b.outside;
}

TEST_CASE("theSunShareKernelIsTheScalarStepOnEveryTarget", "[simd][shadows]") {
  const Scene scene = resolve_scene("sunset", {"viewport.width=320", "viewport.height=256"});
  const SceneResources resources = load_scene_resources(scene);
  const FramePlan frame = make_frame_plan(scene, resources.terrain_values());
  const ShadowPlan plan = make_shadow_plan(scene, frame);
  REQUIRE(plan.enabled);
  REQUIRE(plan.levels > 6);
  // Points at every scale of the levels, from the finest square to past the coarsest, and
  // heights around the cache's surface (below it: no lift; above: lifted horizons).
  test::HashedDraws draws(5);
  const auto unit = [&] { return draws.uniform(0.0, 1.0); };
  const auto point = [&](float& dx, float& dz, float& h) {
    const double reach =
        plan.spacing[0] * std::exp2(unit() * (plan.levels + 1)) * plan.resolution * 0.5;
    const double angle = unit() * 6.283185307179586;
    dx = float(reach * std::cos(angle));
    dz = float(reach * std::sin(angle));
    h = float(-700.0 + 1400.0 * unit());
  };
  const EachTarget targets;
  ShadowWork reached;  // the scalar's branches the points reach, with the sun up and the skip
  // Every level, and the levels [2, levels - 3) alone as a frame builds some (points finer
  // than the first read its first level, points past the last are beyond the cache).
  for (const auto& [first, end] : {std::pair{0, plan.levels}, std::pair{2, plan.levels - 3}}) {
    const SunHorizonCache<float> cache =
        build_horizon_cache<float>(plan, frame, resources, first, end);
    ShadowParams<float> params = make_shadow_params<float>(plan);
    params.first_level = first;
    params.end_level = end;
    for (const bool sun_set : {false, true}) {
      for (const bool skip_lit : {true, false}) {
        params.sun_set = sun_set ? 1 : 0;
        params.skip_lit = skip_lit ? 1 : 0;
        for (const std::size_t width : test::awkward_lengths()) {
          const int w = int(width), rows = 2, stride = 64;
          const std::size_t pixels = std::size_t(rows) * stride;
          std::vector<std::uint32_t> covered(pixels, 0xffffffffu);
          std::vector<float> dx(pixels, 0.0f), dz(pixels, 0.0f), h(pixels, 0.0f);
          for (int j = 0; j < rows; ++j) {
            for (int i = 0; i < w; ++i) {
              const std::size_t k = std::size_t(j) * stride + i;
              covered[k] = unit() < 1.0 / 3.0 ? 0xffffffffu : std::uint32_t(k);
              point(dx[k], dz[k], h[k]);
            }
          }
          std::vector<float> expected(pixels, test::sentinel<float>());
          ShadowWork scalar;
          for (std::size_t k = 0; k < pixels; ++k) {
            if (covered[k] != 0xffffffffu && int(k % stride) < w) {
              expected[k] = sun_visibility<float>(params, cache, dx[k], h[k], dz[k], scalar);
            }
          }
          if (!sun_set && skip_lit) {
            reached += scalar;
          }
          for (const std::string& target : targets.runnable()) {
            simd::force_target(target);
            std::vector<float> got(pixels, test::sentinel<float>());
            ShadowWork vector;
            simd::sun_shares(params, cache, covered, dx, h, dz, w, rows, stride, got, vector);
            INFO(target << ", levels [" << first << ", " << end << "), width " << w << ", sun set "
                        << sun_set << ", skip " << skip_lit);
            REQUIRE(test::same_bits<float>(got, expected));
            REQUIRE(same_work(vector, scalar));
          }
        }
      }
    }
  }
  CHECK(reached.lit > 0);
  CHECK(reached.evaluated > 0);
  CHECK(reached.dark > 0);
  CHECK(reached.outside > 0);
  CHECK(reached.evaluated - reached.dark > 0);  // the penumbra's formula
}

}  // namespace
}  // namespace relief
