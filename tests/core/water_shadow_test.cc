// Cast shadows on the water (core/water.h, pipeline/tile_shadows.h): the sun's share at the
// surface point in front of the ground, which takes the sun glint and the sunlit part of the
// water body. shade_water against the glint's closed form; frames against exact ray casting
// in double from the surface point the pixel's own ray meets, against the whole-frame oracle
// (the stage functions on whole buffers), and by properties that need no oracle: shadows
// only darken; the simd backend's bytes on every target.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "core/sun_horizons.h"
#include "core/water.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/frame_counters.h"
#include "tests/support/shadow_frames.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

// The lake with the sun low ahead of the camera (its glint on the water, the hills' shadows
// reaching toward the camera over the lake), and water that lets no light through beyond a
// unit of depth (extinction at its limit: 2^-144 per unit): there a pixel's colour is the
// surface's alone, whatever the shadow on the ground beneath.
Scene low_sun_lake(bool shadows) {
  return resolve_scene(
      "lake",
      test::small_shadow_frame({"lighting.sun_azimuth_deg=75", "lighting.sun_elevation_deg=10",
                                "water.extinction=[100,100,100]",
                                std::string("lighting.shadows=") + (shadows ? "true" : "false")}));
}

Frame render_with_heights(const Scene& scene) {
  FrameRequest request;
  request.backend = Backend::kReference;
  request.outputs.linear = true;
  request.outputs.primitive = true;
  request.outputs.world_height = true;
  return render_frame(scene, load_scene_resources(scene), request);
}

TEST_CASE("aCastShadowOnTheWaterTakesTheSunGlintAndTheSunlitBodyButNotTheSky", "[shading]") {
  const Scene scene = resolve_scene("lake", {});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan frame = make_frame_plan(scene, lattice);
  const ShadeParams<double> p =
      make_shade_params<double>(make_shading_plan(scene, frame, lattice.size));
  ShadeWork work;
  const Vec3<double> ground{0.3, 0.25, 0.2};
  // The view whose mirror image on a flat surface is the sun (the waves' fine octaves faded
  // out by a huge footprint, the bump by zero depth): the glint at its brightest.
  const Vec3<double> sun = p.sun_direction;
  const Vec3<double> glint_view = normalize_or(Vec3<double>{sun.x, -sun.y, sun.z}, sun);
  const auto water = [&](const Vec3<double>& view, double depth, double share) {
    return shade_water(p, lattice, nullptr, view, 100.0, depth, ground, 1e9, share, {}, 0.0, work);
  };
  const Vec3<double> lit = water(glint_view, 0.0, 1.0);
  const Vec3<double> dark = water(glint_view, 0.0, 0.0);
  // The reflected disc alone goes: Fresnel x reflectivity (0.3 at zero depth) x 20 x the sun,
  // the disc whole (the mirror direction is the sun's). Fresnel from the angle of incidence.
  const double cos_i = sun.y;  // the flat surface's normal is up
  const double fresnel = 0.02 + 0.98 * std::pow(1.0 - cos_i, 5.0);
  const double glint = fresnel * 0.3 * 20.0;
  CHECK(lit.x - dark.x == Approx(glint * p.sun.x).epsilon(1e-6));
  CHECK(lit.y - dark.y == Approx(glint * p.sun.y).epsilon(1e-6));
  CHECK(lit.z - dark.z == Approx(glint * p.sun.z).epsilon(1e-6));
  // Looking away from the glint over shallow water nothing of the sun is seen: unchanged.
  const Vec3<double> away = normalize_or(Vec3<double>{-sun.x, -0.3, -sun.z}, sun);
  const Vec3<double> shallow_lit = water(away, 0.0, 1.0), shallow_dark = water(away, 0.0, 0.0);
  CHECK(shallow_lit.x == shallow_dark.x);
  CHECK(shallow_lit.y == shallow_dark.y);
  CHECK(shallow_lit.z == shallow_dark.z);
  // Deep water's body loses the sun's part, keeps the sky's; linear in the share between.
  const Vec3<double> deep_lit = water(away, 500.0, 1.0), deep_dark = water(away, 500.0, 0.0);
  const Vec3<double> deep_half = water(away, 500.0, 0.5);
  CHECK(deep_dark.x < deep_lit.x);
  CHECK(deep_dark.y > 0.0);
  CHECK(deep_half.y == Approx(0.5 * (deep_lit.y + deep_dark.y)).epsilon(1e-9));
}

TEST_CASE("theWaterInACastShadowLosesTheSunWhereExactRayCastingFindsItsSurfaceShadowed",
          "[shadows]") {
  const Scene on = low_sun_lake(true), off = low_sun_lake(false);
  const Frame lit = render_with_heights(off), shadowed = render_with_heights(on);
  const SceneResources resources = load_scene_resources(on);
  const FramePlan frame = make_frame_plan(on, resources.terrain_values());
  const ShadowPlan plan = make_shadow_plan(on, frame);
  REQUIRE(plan.enabled);
  const CameraFrame camera = make_camera_frame(on.camera, on.viewport);
  const double level = frame.relative_water_level;  // < 0: the camera is above the water
  REQUIRE(level < 0.0);
  const double elevation = on.lighting.sun_elevation_deg * M_PI / 180.0;
  const double radius = on.sky.sun_disc_deg * M_PI / 180.0;
  // Two degrees past the disc's edge either way: a share the cache's sampling cannot move
  // across (its horizons come from four samples around the point, at the level's octaves).
  const double margin = 2.0 * M_PI / 180.0;
  const double dark_slope = std::tan(elevation + radius + margin);
  const double lit_slope = std::tan(elevation - radius - margin);
  const double highest = frame.bounds.world_max - on.camera.position[1];
  // Whether the terrain hides the sun from camera-relative point p by the margin (1), leaves
  // it in view by the margin (0), or neither (-1): a march toward the sun over the terrain
  // function of the finest level that holds the point (stage 3 at its octave count), half its
  // spacing a step, until a sample rises above the dark slope or the lit slope passes over the
  // highest terrain there can be. An occluder within two of the level's spacings counts for
  // neither (it may rise between the samples, which are all the cache sees of it), nor does
  // one past the level's square (the cache sees it through the coarser levels' fewer octaves,
  // sun_horizons.h, which may flatten it).
  const auto shadowed_by_margin = [&](const glm::dvec3& p) {
    for (int l = 0; l < plan.levels; ++l) {
      const double u = p.x * plan.axis_x + p.z * plan.axis_z;
      const double v = p.z * plan.axis_x - p.x * plan.axis_z;
      const double half = 0.5 * (on.lighting.shadow_resolution - 1) * plan.spacing[l];
      if (std::abs(u) >= half || std::abs(v) >= half) {
        continue;
      }
      const double step = plan.spacing[l] / 2;
      const double edge = level_last_u(plan, l) - u;  // the square's end toward the sun
      double slope = -HUGE_VAL;
      for (double t = step; t <= plan.reach && p.y + t * lit_slope <= highest; t += step) {
        const double h = fbm_height<double>(frame.terrain, p.x + t * plan.axis_x,
                                            p.z + t * plan.axis_z, plan.nu[l]);
        slope = std::max(slope, (h - p.y) / t);
        if (slope > dark_slope) {
          return t >= 2 * plan.spacing[l] && t <= edge ? 1 : -1;
        }
      }
      return slope < lit_slope ? 0 : -1;
    }
    return -1;
  };
  const int width = on.viewport.width, height = on.viewport.height;
  const std::size_t pixels = std::size_t(width) * height;
  int in_shadow = 0, darkened = 0, in_sun = 0, kept = 0;
  // Pixels in a scrambled order (a stride prime to the count) until both kinds are plenty.
  for (std::size_t n = 0; n < pixels && (in_shadow < 60 || in_sun < 60); ++n) {
    const std::size_t k = n * 7919 % pixels;
    const int px = int(k % width), py = int(k / width);
    const double ground = double(shadowed.image.world_height[k]) - on.camera.position[1];
    if (shadowed.image.primitive[k] == 0xffffffffu || !(ground < level - 1.0)) {
      continue;  // no water in front of this pixel's ground, or water the ground shows through
    }
    // The pixel's view ray (rows bottom to top) meets the water plane at the surface point.
    const double sx = (2.0 * (px + 0.5) / width - 1.0) * camera.tan_half_fov_x;
    const double sy = (2.0 * (py + 0.5) / height - 1.0) * camera.tan_half_fov_y;
    const glm::dvec3 ray = camera.forward + sx * camera.right + sy * camera.up;
    if (!(ray.y < 0.0)) {
      continue;
    }
    const int verdict = shadowed_by_margin(ray * (level / ray.y));
    bool changed = false;
    for (int c = 0; c < 3; ++c) {
      changed = changed || shadowed.image.linear[3 * k + c] != lit.image.linear[3 * k + c];
    }
    if (verdict == 1) {
      ++in_shadow;
      darkened += changed;
    } else if (verdict == 0) {
      ++in_sun;
      kept += !changed;
    }
  }
  INFO(in_shadow << " sampled water pixels in shadow, " << darkened << " of them changed; "
                 << in_sun << " in the sun, " << kept << " of them unchanged");
  REQUIRE(in_shadow >= 60);
  REQUIRE(in_sun >= 60);
  // The cache sees the terrain only at its samples (a peak between two lowers its horizon) and
  // interpolates four samples' shares (one across a shore, higher, may shade a lit point): a
  // twentieth either way (measured: 60 of 60 shadowed pixels changed, 5007 of 5012 lit kept).
  CHECK(darkened >= in_shadow * 19 / 20);
  CHECK(kept >= in_sun * 19 / 20);
}

TEST_CASE("shadowsOnTheWaterOnlyDarkenAndTheWholeFrameOracleDrawsThem", "[shadows]") {
  const Scene on = low_sun_lake(true), off = low_sun_lake(false);
  const Frame a = test::render_reference_linear(off), b = test::render_reference_linear(on);
  REQUIRE(a.image.linear.size() == b.image.linear.size());
  for (std::size_t k = 0; k < a.image.linear.size(); ++k) {
    REQUIRE(b.image.linear[k] <= a.image.linear[k]);
  }
  // The oracle computes each surface point's share on whole buffers, the backend in tiles.
  const SceneResources resources = load_scene_resources(on);
  CHECK(render_frame(on, resources, FrameRequest{}).image.srgb ==
        render_whole_frame(on, resources).srgb);
}

TEST_CASE("waterShadowFramesAreBitIdenticalOnEveryTargetAndThreadCountAndWithoutTheLitSkip",
          "[shadows][simd]") {
  const EachTarget targets;
  const char* kCounters[] = {"water surface shadow lookups", "water surface points proven lit",
                             "water surface points in full shadow"};
  // The low sun over the lake; with sky light and the cloud layer over it; the glint of a
  // higher sun behind the camera's hills, the body of clear water over shadowed ground.
  const std::vector<Scene> scenes = {
      low_sun_lake(true),
      resolve_scene("lake", test::small_shadow_frame(
                                {"lighting.sun_azimuth_deg=75", "lighting.sun_elevation_deg=10",
                                 "lighting.shadows=true", "lighting.sky_occlusion=true",
                                 "sky.clouds={\"altitude\": 900, \"coverage\": 0.4}"})),
      resolve_scene("lake", test::small_shadow_frame({"lighting.sun_azimuth_deg=260",
                                                      "lighting.sun_elevation_deg=20",
                                                      "lighting.shadows=true"})),
      // Hostile heights: the camera a millimetre above the water (every surface point's
      // ratio level / height tiny, the points at the camera's feet), and the water a hair
      // below the highest terrain seen from far above it (the ratio near 1).
      resolve_scene("lake", test::small_shadow_frame(
                                {"camera.position=[0,95.001,0]", "camera.pitch_deg=-20",
                                 "lighting.sun_azimuth_deg=165", "lighting.sun_elevation_deg=4",
                                 "lighting.shadows=true"})),
      resolve_scene("lake", test::small_shadow_frame(
                                {"camera.position=[0,20000,0]", "camera.pitch_deg=-60",
                                 "terrain.water_level=400", "lighting.sun_elevation_deg=8",
                                 "lighting.shadows=true"})),
  };
  for (const Scene& scene : scenes) {
    const SceneResources resources = load_scene_resources(scene);
    FrameRequest request;
    const Frame reference = test::render_finite(scene, resources, request);
    REQUIRE(test::frame_counter(reference, kCounters[0]) > 0);
    // The lit skip leaves out the share's arithmetic, never its value.
    FrameRequest no_skip = request;
    no_skip.skips.lit_shadows = false;
    const Frame unskipped = render_frame(scene, resources, no_skip);
    CHECK(test::same_bits(unskipped.image.linear, reference.image.linear));
    CHECK(test::frame_counter(unskipped, kCounters[1]) == 0);
    targets.each_with_threads({1, 2}, [&](const std::string& target, int threads) {
      request.backend = Backend::kSimd;
      const Frame got = render_frame(scene, resources, request);
      INFO(target << ", " << threads << " threads");
      REQUIRE(got.image.srgb == reference.image.srgb);
      REQUIRE(test::same_bits(got.image.linear, reference.image.linear));
      for (const char* counter : kCounters) {
        INFO(counter);
        CHECK(test::frame_counter(got, counter) == test::frame_counter(reference, counter));
      }
    });
  }
}

TEST_CASE("aFrameBuildsTheFinerLevelsItsWaterSurfacesReadAndNoSkipChangesItsBytes",
          "[shadows][skip]") {
  // A camera just above the lake looking down: the water's surface points lie much nearer
  // than the ground under them, in finer cache levels than any drawn ground reaches.
  const Scene scene = resolve_scene(
      "lake", test::small_shadow_frame({"camera.position=[0,100,0]", "camera.pitch_deg=-35",
                                        "lighting.sun_azimuth_deg=165",
                                        "lighting.sun_elevation_deg=4", "lighting.shadows=true"}));
  const SceneResources resources = load_scene_resources(scene);
  FrameRequest request;
  request.outputs.linear = true;
  const Frame skipped = render_frame(scene, resources, request);
  REQUIRE(test::frame_counter(skipped, "water surface shadow lookups") > 1000);
  REQUIRE(test::frame_counter(skipped, "water surface points proven lit") <
          test::frame_counter(skipped, "water surface shadow lookups"));
  FrameRequest every_level = request;
  every_level.skips.unread_shadow_levels = false;
  const Frame built = render_frame(scene, resources, every_level);
  CHECK(test::same_bits(skipped.image.linear, built.image.linear));
  // The whole-frame oracle builds every level too.
  CHECK(skipped.image.srgb == render_whole_frame(scene, resources).srgb);
}

}  // namespace
}  // namespace relief
