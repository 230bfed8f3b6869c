// Sky light (core/sky_horizons.h): the four sweeps against a brute-force search of every
// sample's horizons, the per-pixel share against exact ray casting in double over the terrain
// function (in the cache's four directions, and in 32), and frame properties that need no
// oracle: sky light only darkens, a flat terrain's sky is wholly open, a set sun leaves it on.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/scene/scene_json.h"
#include "core/sky_horizons.h"
#include "core/sun_horizons.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"
#include "tests/support/frame_counters.h"
#include "tests/support/hashed_draws.h"
#include "tests/support/shadow_frames.h"

namespace relief {
namespace {

constexpr int kSamples = 32;

// Two levels of 32 samples, level 1 twice as coarse, both about the camera, every row and
// column of level 0 strictly between two of level 1's; occluders up to `reach` past a line.
ShadowParams<double> nested_levels(double reach) {
  ShadowPlan plan;
  plan.sky = true;
  plan.resolution = kSamples;
  plan.levels = 2;
  plan.axis_x = 1.0;
  plan.axis_z = 0.0;
  for (int level = 0; level < 2; ++level) {
    plan.spacing[level] = std::exp2(level);
    plan.nu[level] = 1;
  }
  plan.origin_u[0] = -16.0 + 0.3;
  plan.origin_u[1] = -32.0 + 0.55;
  plan.origin_v[0] = -16.0 + 0.25;
  plan.origin_v[1] = -32.0 + 0.6;
  plan.sky_reach = reach;
  return make_shadow_params<double>(plan);
}

// One direction's openness from the angles themselves (atan, cos), not from the tangent
// identity the stage uses: cos^2 e_h / cos^2 e_p above the plane, 1 at or below it.
double exact_openness(double horizon, double plane) {
  const double e_h = std::atan(horizon), e_p = std::atan(std::max(0.0, plane));
  if (e_h <= e_p) {
    return 1.0;
  }
  return std::cos(e_h) * std::cos(e_h) / (std::cos(e_p) * std::cos(e_p));
}

// The brute-force horizon of sample `at` of a line given as (position along the direction,
// height) points, the line's own samples first: the largest slope to any point ahead.
double brute_horizon(const std::vector<std::pair<double, double>>& line, int at) {
  double best = -HUGE_VAL;
  for (const auto& [along, h] : line) {
    if (along > line[at].first) {
      best = std::max(best, (h - line[at].second) / (along - line[at].first));
    }
  }
  return best;
}

TEST_CASE("theSkySweepsFindEverySamplesOpennessAsABruteForceSearchDoes", "[sky]") {
  for (const double reach : {1e9, 5.0}) {
    const ShadowParams<double> p = nested_levels(reach);
    SunHorizonCache<double> cache;
    cache.allocate(kSamples, 0, 2, false, true);
    test::HashedDraws draws(13);
    for (double& h : cache.height) {
      h = draws.uniform(-50.0, 50.0);
    }
    for (int level = 0; level < 2; ++level) {
      sweep_sun_horizons<double>(p, level, RowRange{0, kSamples}, cache);
    }
    for (int level = 0; level < 2; ++level) {
      sweep_sky_columns<double>(p, level, RowRange{0, kSamples}, cache);
    }
    const auto height = [&](int level, bool along_v, int line, int at) {
      return along_v ? cache.height[cache.index(level, at, line)]
                     : cache.height[cache.index(level, line, at)];
    };
    for (int level = 0; level < 2; ++level) {
      for (int row = 0; row < kSamples; ++row) {
        for (int column = 0; column < kSamples; ++column) {
          double sum = 0.0;
          for (const bool along_v : {false, true}) {
            for (const double sign : {1.0, -1.0}) {
              // The line through the sample along the direction: its own samples, then
              // (level 0) level 1's past its far end up to the reach and one sample more,
              // heights interpolated between level 1's two lines around it.
              const double* origin_along = along_v ? p.origin_v : p.origin_u;
              const double* origin_across = along_v ? p.origin_u : p.origin_v;
              const int line = along_v ? column : row, at = along_v ? row : column;
              std::vector<std::pair<double, double>> points;
              for (int t = 0; t < kSamples; ++t) {
                points.push_back({sign * (origin_along[level] + t * p.spacing[level]),
                                  height(level, along_v, line, t)});
              }
              if (level == 0) {
                const double far_end = std::max(points.front().first, points.back().first);
                const double across = origin_across[0] + line * p.spacing[0];
                const double fj = (across - origin_across[1]) / p.spacing[1];
                const int j0 = int(std::floor(fj));
                const double g = fj - j0;
                REQUIRE(g > 0.1);
                REQUIRE(g < 0.9);
                for (int t = 0; t < kSamples; ++t) {
                  const double a = sign * (origin_along[1] + t * p.spacing[1]);
                  if (a > far_end && a <= far_end + reach + p.spacing[1]) {
                    const double h0 = height(1, along_v, j0, t), h1 = height(1, along_v, j0 + 1, t);
                    points.push_back({a, h0 + (h1 - h0) * g});
                  }
                }
              }
              // The plane: the central difference toward the direction, one-sided at the ends.
              const int ahead = std::clamp(at + int(sign), 0, kSamples - 1);
              const int behind = std::clamp(at - int(sign), 0, kSamples - 1);
              const double plane = (points[ahead].second - points[behind].second) /
                                   (points[ahead].first - points[behind].first);
              sum += exact_openness(brute_horizon(points, at), plane);
            }
          }
          INFO("reach " << reach << ", level " << level << " row " << row << " column " << column);
          CHECK(cache.sky[cache.index(level, row, column)] ==
                Approx(sum / 4).epsilon(1e-12).margin(1e-12));
        }
      }
    }
  }
}

TEST_CASE("theOpennessOfOneDirectionStaysInItsDomain", "[sky]") {
  CHECK(sky_openness(0.0f, 0.0f) == 1.0f);
  CHECK(sky_openness(-3.0f, 0.0f) == 1.0f);  // a horizon below the point
  CHECK(sky_openness(0.5f, 0.7f) == 1.0f);   // no higher than the plane
  CHECK(sky_openness(1.0f, -5.0f) == 0.5f);  // 45 degrees over ground falling away
  CHECK(sky_openness(NAN, 0.0f) == 1.0f);    // not a horizon: nothing hidden
  CHECK(sky_openness(1e30f, 0.0f) == Approx(1e-12f).margin(1e-12));
  CHECK(sky_openness(INFINITY, INFINITY) == 1.0f);
  CHECK(std::isfinite(sky_openness(3e38f, 2e38f)));
  test::HashedDraws draws(3);
  for (int k = 0; k < 1000; ++k) {
    const double horizon = draws.uniform(-4.0, 4.0), plane = draws.uniform(-4.0, 4.0);
    CHECK(sky_openness(horizon, plane) == Approx(exact_openness(horizon, plane)).epsilon(1e-12));
  }
}

// The level a lookup reads at camera-relative (dx, dz): the finest whose samples surround it.
int cache_level_at(const ShadowParams<double>& p, double dx, double dz) {
  const double u = dx * p.axis_x + dz * p.axis_z, v = dz * p.axis_x - dx * p.axis_z;
  for (int level = 0; level < p.levels; ++level) {
    double fi = 0, fj = 0;
    if (level_coordinates(p, level, u, v, fi, fj)) {
      return level;
    }
  }
  return -1;
}

TEST_CASE("theCachedSkyShareIsCloseToExactRayCastingInDouble", "[sky]") {
  // Ground points around the camera of the default scene. The oracle marches the terrain
  // function the point's level carries (stage 3 in double at its octave count) in each
  // direction, a step of a quarter of the level's spacing growing to 1% of the distance, out
  // to the cache's whole extent (past the sky's reach); the plane is the function's central
  // difference over the level's spacing; each direction's openness comes from the angles
  // themselves. In the cache's four directions it differs by the cache's sampling; in 32 it also
  // differs by the four's discretisation of the azimuth.
  const Scene scene = resolve_scene(
      "default", {"lighting.sky_occlusion=true", "viewport.width=320", "viewport.height=256"});
  const SceneResources resources = load_scene_resources(scene);
  const FramePlan frame = make_frame_plan(scene, resources.terrain_values());
  const ShadowPlan plan = make_shadow_plan(scene, frame);
  REQUIRE(plan.sky);
  REQUIRE(!plan.enabled);
  const ShadowParams<double> params = make_shadow_params<double>(plan);
  const SunHorizonCache<double> cache = build_horizon_cache<double>(plan, frame, resources);
  test::HashedDraws draws(17);
  SkyWork work;
  double four_sum = 0.0, four_worst = 0.0, many_sum = 0.0, many_worst = 0.0, occluded = 0.0;
  constexpr int kPoints = 40, kAzimuths = 32;
  for (int k = 0; k < kPoints; ++k) {
    const double dx = draws.uniform(-3000.0, 3000.0), dz = draws.uniform(-3000.0, 3000.0);
    const int level = cache_level_at(params, dx, dz);
    REQUIRE(level >= 0);
    const double nu = plan.nu[level], s = plan.spacing[level];
    const auto terrain = [&](double x, double z) {
      return fbm_height<double>(frame.terrain, x, z, nu);
    };
    const double h = terrain(dx, dz);
    // Past the sky's reach too: the whole cache's extent, to count what the reach leaves out.
    const double far = plan.spacing[plan.levels - 1] * (plan.resolution / 2 - 2);
    const auto openness = [&](double ax, double az) {
      double horizon = -HUGE_VAL;
      for (double t = s / 4; t <= far; t += std::max(s / 4, 0.01 * t)) {
        horizon = std::max(horizon, (terrain(dx + t * ax, dz + t * az) - h) / t);
      }
      const double plane =
          (terrain(dx + s * ax, dz + s * az) - terrain(dx - s * ax, dz - s * az)) / (2 * s);
      return exact_openness(horizon, plane);
    };
    // The cache's four directions: toward the sun's azimuth and away, and to either side.
    const double ax = plan.axis_x, az = plan.axis_z;
    const double four =
        (openness(ax, az) + openness(-ax, -az) + openness(-az, ax) + openness(az, -ax)) / 4;
    double many = 0.0;
    for (int a = 0; a < kAzimuths; ++a) {
      const double angle = 2 * M_PI * a / kAzimuths;
      many += openness(std::cos(angle), std::sin(angle)) / kAzimuths;
    }
    const double cached = sky_visibility<double>(params, cache, dx, dz, work);
    four_sum += std::abs(cached - four);
    four_worst = std::max(four_worst, std::abs(cached - four));
    many_sum += std::abs(cached - many);
    many_worst = std::max(many_worst, std::abs(cached - many));
    occluded += 1.0 - many;
  }
  INFO("four directions: mean |error| " << four_sum / kPoints << ", worst " << four_worst
                                        << "; 32 directions: mean " << many_sum / kPoints
                                        << ", worst " << many_worst << "; mean occlusion "
                                        << occluded / kPoints);
  CHECK(four_sum / kPoints < 0.03);
  CHECK(many_sum / kPoints < 0.05);
  CHECK(occluded / kPoints > 0.02);  // the test has terrain that hides sky to measure
  CHECK(work.outside == 0);
}

TEST_CASE("skyLightOnlyDarkensAndHidesSkyInTheValleys", "[sky]") {
  // The sky's colour is brighter than the ground's in every channel in these scenes: hiding
  // sky can only darken (water, fog and the atmosphere are monotone in the terrain's light,
  // up to rounding).
  for (const char* preset : {"default", "lake", "sunset"}) {
    const Scene off =
        resolve_scene(preset, test::small_shadow_frame({"lighting.sky_occlusion=false"}));
    Scene on = off;
    on.lighting.sky_occlusion = true;
    const Frame a = test::render_reference_linear(off), b = test::render_reference_linear(on);
    REQUIRE(a.image.linear.size() == b.image.linear.size());
    INFO(preset);
    std::size_t darker = 0;
    for (std::size_t k = 0; k < a.image.linear.size(); ++k) {
      // To float rounding: the fog's mix rounds at its colour's magnitude, so a pixel it
      // all but covers may come out a few units in the last place brighter.
      INFO("value " << k);
      REQUIRE(b.image.linear[k] <= a.image.linear[k] * (1.0f + 1e-5f));
      darker += b.image.linear[k] < a.image.linear[k];
    }
    CHECK(darker > a.image.linear.size() / 20);  // lake: mostly water and sky
    CHECK(test::frame_counter(b, "sky lookups") > 0);
    CHECK(test::frame_counter(b, "pixels beyond the sky's cache") == 0);
  }
}

TEST_CASE("aFlatTerrainLeavesTheWholeSkyOpen", "[sky]") {
  const Scene off = resolve_scene(
      "default", test::small_shadow_frame({"terrain.amplitude=1e-3", "terrain.water_level=null"}));
  Scene on = off;
  on.lighting.sky_occlusion = true;
  const Frame a = test::render_reference_linear(off), b = test::render_reference_linear(on);
  CHECK(a.image.linear == b.image.linear);
  CHECK(a.image.srgb == b.image.srgb);
}

TEST_CASE("skyLightStaysOnAfterSunsetAndIsRefusedOnAPlanet", "[sky]") {
  // The sun set: no sun's horizons, but the sky's cache is built and read.
  const Scene night = resolve_scene(
      "sunset",
      test::small_shadow_frame({"lighting.sun_elevation_deg=-20", "lighting.shadows=true"}));
  Scene open = night;
  open.lighting.sky_occlusion = false;
  const Frame a = test::render_reference_linear(night), b = test::render_reference_linear(open);
  CHECK(test::frame_counter(a, "cache levels built") > 0);
  CHECK(test::frame_counter(a, "pixels in full shadow") ==
        test::frame_counter(a, "shadow lookups"));
  std::size_t darker = 0;
  for (std::size_t k = 0; k < a.image.linear.size(); ++k) {
    REQUIRE(std::isfinite(a.image.linear[k]));
    REQUIRE(a.image.linear[k] <= b.image.linear[k]);
    darker += a.image.linear[k] < b.image.linear[k];
  }
  CHECK(darker > 0);
  CHECK_THROWS_WITH(resolve_scene("planet", {"lighting.sky_occlusion=true"}),
                    Catch::Contains("lighting.sky_occlusion") && Catch::Contains("planet"));
  CHECK_THROWS_WITH(resolve_scene("default", {"lighting.sky_occlusion=1"}),
                    Catch::Contains("lighting.sky_occlusion"));
}

TEST_CASE("theWholeFrameOracleDrawsTheSkyLitFrameTheBackendDraws", "[sky]") {
  // The oracle calls the stage functions on whole buffers, the backend in tiles and tasks.
  for (const char* shadows : {"lighting.shadows=true", "lighting.shadows=false"}) {
    const Scene scene = resolve_scene("sunset", test::small_shadow_frame({shadows}));
    REQUIRE(scene.lighting.sky_occlusion);
    const SceneResources resources = load_scene_resources(scene);
    FrameRequest request;
    request.backend = Backend::kReference;
    const FrameImage tiled = render_frame(scene, resources, request).image;
    const FrameImage whole = render_whole_frame(scene, resources);
    INFO(shadows);
    CHECK(tiled.srgb == whole.srgb);
  }
}

}  // namespace
}  // namespace relief
