// The terrain reflected in the water (core/water_reflection.h): the block maxima bound the
// surface they let rays skip; reflected rays against a march over the terrain's own function
// in double (stage 3 at the level's octaves, every quarter spacing, no skipping: an oracle that
// reads no cache); degenerate rays; the scene field's refusals. The frames are
// tests/pipeline/reflection_frame_test.cc's.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/scene/scene_json.h"
#include "core/sun_horizons.h"
#include "core/water_reflection.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/frame_counters.h"
#include "tests/support/hashed_draws.h"
#include "tests/support/shadow_frames.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

// The mirror preset shrunk (shadow_frames.h), with `more` overrides.
Scene small_mirror(std::vector<std::string> more = {}) {
  return resolve_scene("mirror", test::small_shadow_frame(std::move(more)));
}

// A cache of every level for `scene` (the whole-frame oracle's composition), its plan rounded
// to double, and the frame's plan.
struct Cache {
  FramePlan frame;
  ShadowPlan plan;
  ShadowParams<double> params;
  SunHorizonCache<double> heights;
  HeightBlockMaxima<double> maxima;
};
Cache build_cache(const Scene& scene, const SceneResources& resources) {
  Cache c;
  c.frame = make_frame_plan(scene, resources.terrain_values());
  c.plan = make_shadow_plan(scene, c.frame);
  c.params = make_shadow_params<double>(c.plan);
  c.heights = build_horizon_cache<double>(c.plan, c.frame, resources);
  build_height_block_maxima(c.params, c.heights, 0, c.plan.levels, c.maxima);
  return c;
}

// The finest level holding camera-relative (u, v) and the bilinear surface there; false
// where none does.
bool surface_at(const Cache& c, double u, double v, int& level, double& h) {
  for (level = 0; level < c.plan.levels; ++level) {
    double fi = 0, fj = 0;
    if (level_coordinates(c.params, level, u, v, fi, fj)) {
      const int i = int(fi), j = int(fj);
      const double f = fi - i, g = fj - j;
      const auto at = [&](int jj, int ii) {
        return c.heights.height[c.heights.index(level, jj, ii)];
      };
      h = (at(j, i) + (at(j, i + 1) - at(j, i)) * f) * (1 - g) +
          (at(j + 1, i) + (at(j + 1, i + 1) - at(j + 1, i)) * f) * g;
      return true;
    }
  }
  return false;
}

TEST_CASE("theBlockMaximaBoundTheFinestSurfaceInsideEveryBlockOfEveryLevel", "[reflections]") {
  // A camera off every level's lattice and a sun off the axes: the finer levels' squares
  // straddle the coarser ones' blocks at fractions of a sample.
  const Scene scene =
      small_mirror({"camera.position=[123.4,160,-77.7]", "lighting.sun_azimuth_deg=37"});
  const SceneResources resources = load_scene_resources(scene);
  const Cache c = build_cache(scene, resources);
  REQUIRE(c.plan.reflections);
  REQUIRE(c.maxima.tiers >= 2);
  test::HashedDraws draws(41);
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    // Points spread over every level's square: a distance drawn on a log scale.
    const double reach = 0.5 * (c.plan.resolution - 1) * c.plan.spacing[c.plan.levels - 1];
    const double r = std::exp(draws.uniform(std::log(c.plan.spacing[0]), std::log(reach)));
    const double a = draws.uniform(0.0, 2.0 * M_PI);
    const double u = r * std::cos(a), v = r * std::sin(a);
    int finest = 0;
    double h = 0;
    if (!surface_at(c, u, v, finest, h)) {
      continue;
    }
    ++checked;
    // Every level holding the point, the finest and the coarser ones: its blocks of every
    // tier, and the level's top, lie no lower than the surface a ray there meets.
    for (int level = finest; level < c.plan.levels; ++level) {
      double fi = 0, fj = 0;
      if (!level_coordinates(c.params, level, u, v, fi, fj)) {
        continue;
      }
      INFO("level " << level << " of finest " << finest << " at (" << u << ", " << v << ")");
      REQUIRE(c.maxima.level_top[level] >= h);
      for (int tier = 0; tier < c.maxima.tiers; ++tier) {
        const int shift = kReflectionBlockLog2 + tier;
        REQUIRE(c.maxima.at(tier, level, int(fj) >> shift, int(fi) >> shift) >= h);
      }
    }
    REQUIRE(c.maxima.top >= h);
  }
  CHECK(checked > 15000);
}

TEST_CASE("reflectedRaysMeetTheTerrainWhereAMarchOverTheTerrainFunctionDoes", "[reflections]") {
  const Scene scene = small_mirror();
  const SceneResources resources = load_scene_resources(scene);
  const Cache c = build_cache(scene, resources);
  const double level = c.frame.relative_water_level;
  REQUIRE(level < 0.0);
  const double highest = c.frame.bounds.world_max - scene.camera.position[1];
  // The oracle: the terrain function itself at the octave count of the finest level holding
  // the point (what the cache samples there), a quarter of that level's spacing a step, from
  // the surface until the ray rises above the highest terrain or leaves the levels; the first
  // step below the terrain, refined by bisection.
  const auto oracle_terrain = [&](double x, double z, double& h) {
    const double u = x * c.plan.axis_x + z * c.plan.axis_z;
    const double v = z * c.plan.axis_x - x * c.plan.axis_z;
    int finest = 0;
    double cached = 0;
    if (!surface_at(c, u, v, finest, cached)) {
      return -1;
    }
    h = fbm_height<double>(c.frame.terrain, x, z, c.plan.nu[finest]);
    return finest;
  };
  const auto oracle_march = [&](const Vec3<double>& s, const Vec3<double>& d, double& hit) {
    double t = 0, previous = 0;
    for (int step = 0; step < 400000; ++step) {
      const Vec3<double> p = s + d * t;
      double h = 0;
      const int l = oracle_terrain(p.x, p.z, h);
      if (l < 0 || p.y > highest) {
        return false;
      }
      if (p.y < h) {
        double lo = previous, hi = t;
        for (int k = 0; k < 30; ++k) {
          const double mid = 0.5 * (lo + hi);
          const Vec3<double> q = s + d * mid;
          double hm = 0;
          (oracle_terrain(q.x, q.z, hm) >= 0 && q.y < hm ? hi : lo) = mid;
        }
        hit = hi;
        return true;
      }
      previous = t;
      t += 0.25 * c.plan.spacing[l] / std::max(1e-9, std::hypot(d.x, d.z));
    }
    return false;
  };
  test::HashedDraws draws(97);
  int rays = 0, hits = 0, agree = 0, close = 0, oracle_hits = 0;
  while (rays < 300) {
    // A surface point well under water (no shore within reach of its cell) and a direction
    // rising 1 to 25 degrees: hits on the near hills and escapes over them.
    const double x = draws.uniform(-1500, 1500), z = draws.uniform(-1500, 1500);
    double ground = 0;
    if (oracle_terrain(x, z, ground) < 0 || !(ground < level - 5.0)) {
      continue;
    }
    const double azimuth = draws.uniform(0, 2 * M_PI);
    const double elevation = draws.uniform(1, 25) * M_PI / 180;
    const Vec3<double> start{x, level, z};
    const Vec3<double> d{std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                         std::cos(elevation) * std::sin(azimuth)};
    ReflectionHit<double> got;
    ReflectionWork work;
    const bool traced = trace_reflection(c.params, c.heights, c.maxima, start, d, got, work);
    double expected = 0;
    const bool marched = oracle_march(start, d, expected);
    ++rays;
    hits += traced;
    oracle_hits += marched;
    agree += traced == marched;
    if (traced && marched) {
      // Within two spacings of the level the hit lies in (the cache's bilinear cells against
      // the function they sample) along the ground.
      const Vec3<double> p = start + d * expected;
      const double u = p.x * c.plan.axis_x + p.z * c.plan.axis_z;
      const double v = p.z * c.plan.axis_x - p.x * c.plan.axis_z;
      int l = 0;
      double h = 0;
      REQUIRE(surface_at(c, u, v, l, h));
      close += std::abs(got.distance - expected) * std::hypot(d.x, d.z) <= 2 * c.plan.spacing[l];
      REQUIRE(std::isfinite(got.point.x));
      REQUIRE(std::isfinite(got.slope_x));
    }
  }
  INFO(rays << " rays: " << hits << " hits traced, " << oracle_hits << " by the oracle, " << agree
            << " agreeing, " << close << " of the common hits within two spacings");
  // Both kinds plenty; a grazing ray may pass a crest one surface has and the other not
  // (a 50th of the rays), a common hit land in the next cells (a 20th).
  REQUIRE(oracle_hits >= 40);
  REQUIRE(rays - oracle_hits >= 40);
  CHECK(agree >= rays * 49 / 50);
  const int common = std::min(hits, oracle_hits);
  CHECK(close >= common * 19 / 20);
}

TEST_CASE("aRayStraightUpOrAlongTheWaterEscapesAndNoneLeavesNaN", "[reflections]") {
  const Scene scene = small_mirror();
  const SceneResources resources = load_scene_resources(scene);
  const Cache c = build_cache(scene, resources);
  const double level = c.frame.relative_water_level;
  ReflectionHit<double> hit;
  ReflectionWork work;
  // Straight up from open water (a point whose cached surface is the raised water): its
  // column holds the water, which it leaves rising.
  Vec3<double> open{0, level, 0};
  bool found = false;
  for (double x = 50; x < 3000 && !found; x += 50) {
    for (double z = -3000; z < 3000 && !found; z += 50) {
      const double u = x * c.plan.axis_x + z * c.plan.axis_z;
      const double v = z * c.plan.axis_x - x * c.plan.axis_z;
      int l = 0;
      double h = 0;
      if (surface_at(c, u, v, l, h) && h == level) {
        open = Vec3<double>{x, level, z};
        found = true;
      }
    }
  }
  REQUIRE(found);
  CHECK_FALSE(
      trace_reflection(c.params, c.heights, c.maxima, open, Vec3<double>{0, 1, 0}, hit, work));
  // Along the water's surface: it meets the first shore ahead (a point on the ray, on the
  // cached surface above the water), or leaves the cache; never loops.
  int met_shore = 0;
  for (double a = 0; a < 6.28; a += 0.25) {
    const Vec3<double> d{std::cos(a), 0, std::sin(a)};
    if (trace_reflection(c.params, c.heights, c.maxima, open, d, hit, work)) {
      ++met_shore;
      REQUIRE(hit.distance > 0);
      CHECK(std::abs(hit.point.x - (open.x + d.x * hit.distance)) < 1e-6 * hit.distance + 1e-9);
      CHECK(std::abs(hit.point.z - (open.z + d.z * hit.distance)) < 1e-6 * hit.distance + 1e-9);
      CHECK(hit.point.y >= level);
    }
  }
  CHECK(met_shore > 0);
  CHECK(work.rays == work.hits + work.above + work.left);
  // Beyond every level: left at once.
  CHECK_FALSE(trace_reflection(c.params, c.heights, c.maxima, Vec3<double>{1e12, level, 0},
                               Vec3<double>{1, 0.1, 0}, hit, work));
}

TEST_CASE("reflectionsAreRefusedOnAPlanetAndAsAnythingButABooleanNamingTheField", "[reflections]") {
  CHECK_THROWS_WITH(resolve_scene("planet", {"water.reflect_terrain=true"}),
                    Catch::Contains("water.reflect_terrain") && Catch::Contains("planet"));
  CHECK_THROWS_WITH(resolve_scene("mirror", {"water.reflect_terrain=1"}),
                    Catch::Contains("water.reflect_terrain"));
  CHECK_THROWS_WITH(resolve_scene("mirror", {"water.reflect_terrain=\"yes\""}),
                    Catch::Contains("water.reflect_terrain"));
  // Without water there is nothing to reflect in: accepted on a planet too.
  CHECK_NOTHROW(
      resolve_scene("planet", {"terrain.water_level=null", "water.reflect_terrain=true"}));
}

}  // namespace
}  // namespace relief
