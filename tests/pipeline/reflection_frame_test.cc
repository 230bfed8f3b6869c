// The terrain reflected in the water in whole frames (pipeline/tile_reflections.h), by
// properties that need no oracle: only water pixels change; no skip changes a byte; the simd
// backend's bytes on every target and thread count; finite under hostile cameras and suns; no
// pass where nothing reflects; and against the whole-frame oracle (the stage functions on
// whole buffers).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/frame_counters.h"
#include "tests/support/shadow_frames.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

// The mirror preset shrunk (shadow_frames.h), with `more` overrides.
Scene small_mirror(std::vector<std::string> more = {}) {
  return resolve_scene("mirror", test::small_shadow_frame(std::move(more)));
}

// The counter `name` summed over the frame's stages, 0 where no stage reports it (a pass that
// did not run).
std::uint64_t counter_or_zero(const Frame& frame, const std::string& name) {
  std::uint64_t sum = 0;
  for (const StageTime& stage : frame.stats.stages) {
    for (const WorkCounter& c : stage.counters) {
      sum += c.name == name ? c.value : 0;
    }
  }
  return sum;
}

// Which pixels have water in front of their ground: reference frame's world heights below the
// water level.
std::vector<bool> water_in_front(const Scene& scene, const SceneResources& resources) {
  FrameRequest request;
  request.outputs.world_height = true;
  request.outputs.primitive = true;
  const Frame f = render_frame(scene, resources, request);
  std::vector<bool> water(f.image.world_height.size());
  for (std::size_t k = 0; k < water.size(); ++k) {
    water[k] =
        f.image.primitive[k] != 0xffffffffu && f.image.world_height[k] < *scene.terrain.water_level;
  }
  return water;
}

TEST_CASE("reflectionsChangeOnlyTheWaterAndNoSkipChangesAByte", "[reflections][skip]") {
  const Scene on = small_mirror(), off = small_mirror({"water.reflect_terrain=false"});
  const SceneResources resources = load_scene_resources(on);
  {
    // Looking down at the lake from 900 units above it: the drawn extent ends far inside the
    // levels laid out (11 of 21 would be built for the pixels alone), where the skip of
    // unread levels would end the shadows' cache and its rows' sweeps but for the
    // reflections, whose rays and hits read past the farthest pixel.
    const Scene down = small_mirror({"camera.position=[0,1000,0]", "camera.pitch_deg=-35"});
    FrameRequest request;
    request.outputs.linear = true;
    const Frame skipped = render_frame(down, resources, request);
    REQUIRE(test::frame_counter(skipped, "reflected rays meeting the terrain") > 100);
    FrameRequest every_level = request;
    every_level.skips.unread_shadow_levels = false;
    CHECK(test::same_bits(render_frame(down, resources, every_level).image.linear,
                          skipped.image.linear));
  }
  FrameRequest request;
  request.outputs.linear = true;
  const Frame a = render_frame(off, resources, request), b = render_frame(on, resources, request);
  const std::vector<bool> water = water_in_front(on, resources);
  std::size_t changed = 0;
  for (std::size_t k = 0; k < water.size(); ++k) {
    const bool differs = a.image.linear[3 * k] != b.image.linear[3 * k] ||
                         a.image.linear[3 * k + 1] != b.image.linear[3 * k + 1] ||
                         a.image.linear[3 * k + 2] != b.image.linear[3 * k + 2];
    REQUIRE((!differs || water[k]));
    changed += differs;
  }
  CHECK(changed > 1000);
  REQUIRE(test::frame_counter(b, "reflected rays meeting the terrain") > 500);
  CHECK(test::frame_counter(b, "blocks skipped below a reflected ray") > 0);
  // Every level built, every lit pixel's share evaluated: the same bytes.
  for (const int skip : {0, 1}) {
    FrameRequest no_skip = request;
    (skip == 0 ? no_skip.skips.unread_shadow_levels : no_skip.skips.lit_shadows) = false;
    CHECK(test::same_bits(render_frame(on, resources, no_skip).image.linear, b.image.linear));
  }
  // Off, no pass runs: the paper's water.
  CHECK(counter_or_zero(a, "reflected rays marched") == 0);
}

TEST_CASE("theWholeFrameOracleDrawsTheSameReflections", "[reflections]") {
  // The oracle marches over every level, the backend over those its pixels reach: a ray
  // that would leave the latter meets the terrain past them only in the oracle.
  const Scene scene = small_mirror();
  const SceneResources resources = load_scene_resources(scene);
  const FrameImage oracle = render_whole_frame(scene, resources);
  const FrameImage got = render_frame(scene, resources, FrameRequest{}).image;
  REQUIRE(got.srgb.size() == oracle.srgb.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < got.srgb.size(); k += 3) {
    differ += got.srgb[k] != oracle.srgb[k] || got.srgb[k + 1] != oracle.srgb[k + 1] ||
              got.srgb[k + 2] != oracle.srgb[k + 2];
  }
  INFO(differ << " of " << got.srgb.size() / 3 << " pixels differ");
  CHECK(differ * 1000 <= got.srgb.size() / 3);
}

TEST_CASE("reflectionFramesAreBitIdenticalOnEveryTargetAndThreadCountAndFinite",
          "[reflections][simd]") {
  const EachTarget targets;
  const char* kCounters[] = {"reflected rays marched", "reflected rays meeting the terrain"};
  const std::vector<Scene> scenes = {
      small_mirror(),
      // The cloud layer over it; no shadows or sky light (the cache's heights alone); the sun
      // set (no sweep at all); rough water (folded rays); the camera a millimetre above the
      // water; the water near the terrain's top seen from 20 km; the finest cache.
      small_mirror({"sky.clouds={\"altitude\": 900, \"coverage\": 0.4}"}),
      small_mirror({"lighting.shadows=false", "lighting.sky_occlusion=false"}),
      small_mirror({"lighting.sun_elevation_deg=-8", "lighting.sky_occlusion=false"}),
      small_mirror({"water.wave_strength=2", "water.wave_length=3"}),
      small_mirror({"camera.position=[0,95.001,0]", "camera.pitch_deg=-20"}),
      small_mirror(
          {"camera.position=[0,20000,0]", "camera.pitch_deg=-60", "terrain.water_level=400"}),
      resolve_scene("mirror", {"viewport.width=96", "viewport.height=64", "grid.width=96",
                               "grid.height=96", "lighting.shadow_resolution=1024"}),
  };
  for (const Scene& scene : scenes) {
    const SceneResources resources = load_scene_resources(scene);
    FrameRequest request;
    const Frame reference = test::render_finite(scene, resources, request);
    REQUIRE(test::frame_counter(reference, kCounters[0]) > 0);
    targets.each_with_threads({1, 2}, [&](const std::string& target, int threads) {
      request.backend = Backend::kSimd;
      const Frame got = render_frame(scene, resources, request);
      INFO(target << ", " << threads << " threads");
      REQUIRE(test::same_bits(got.image.linear, reference.image.linear));
      for (const char* counter : kCounters) {
        INFO(counter);
        CHECK(test::frame_counter(got, counter) == test::frame_counter(reference, counter));
      }
    });
  }
}

TEST_CASE("reflectionsWithoutTerrainUnderWaterOrWithoutWaterRunNoPass", "[reflections][skip]") {
  // The water below every height in view, and no water at all: the same bytes as without.
  for (const char* level : {"terrain.water_level=-5000", "terrain.water_level=null"}) {
    // No cast shadows or sky light: nothing else builds the cache.
    const Scene on =
                    small_mirror({level, "lighting.shadows=false", "lighting.sky_occlusion=false"}),
                off = small_mirror({level, "lighting.shadows=false", "lighting.sky_occlusion=false",
                                    "water.reflect_terrain=false"});
    const SceneResources resources = load_scene_resources(on);
    FrameRequest request;
    request.outputs.linear = true;
    const Frame a = render_frame(on, resources, request), b = render_frame(off, resources, request);
    INFO(level);
    CHECK(test::same_bits(a.image.linear, b.image.linear));
    CHECK(counter_or_zero(a, "reflected rays marched") == 0);
    CHECK(counter_or_zero(a, "cache samples evaluated") == 0);
  }
}

}  // namespace
}  // namespace relief
