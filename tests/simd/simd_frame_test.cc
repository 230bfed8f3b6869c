// Whole frames of the simd backend against the reference backend, on every target compiled in
// that this CPU can run, each forced in turn: every preset, every output, every skip on and off,
// odd sizes, and 1, 2 and 8 threads, all bit-identical with the same work counters. The kernels
// one by one: tests/simd/simd_test.cc and tests/simd/*_kernel_ranges_test.cc.
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

FrameRequest all_outputs(Backend backend) {
  FrameRequest request;
  request.backend = backend;
  request.outputs = {true, true, true, true, true, true};
  return request;
}

void require_same_frames(const Frame& a, const Frame& b) {
  REQUIRE(a.image.srgb == b.image.srgb);
  REQUIRE(test::same_bits<float>(a.image.linear, b.image.linear));
  REQUIRE(test::same_bits<float>(a.image.depth, b.image.depth));
  REQUIRE(a.image.primitive == b.image.primitive);
  REQUIRE(test::same_bits<float>(a.image.normal, b.image.normal));
  REQUIRE(test::same_bits<float>(a.image.world_height, b.image.world_height));
  REQUIRE(test::same_bits<float>(a.image.octaves, b.image.octaves));
  // The same work, stage by stage (the times differ, the counters must not).
  REQUIRE(a.stats.stages.size() == b.stats.stages.size());
  for (std::size_t s = 0; s < a.stats.stages.size(); ++s) {
    INFO(a.stats.stages[s].name);
    REQUIRE(a.stats.stages[s].counters.size() == b.stats.stages[s].counters.size());
    for (std::size_t c = 0; c < a.stats.stages[s].counters.size(); ++c) {
      CHECK(a.stats.stages[s].counters[c].value == b.stats.stages[s].counters[c].value);
    }
  }
}

TEST_CASE("everyPresetRendersBitIdenticallyWithTheSimdBackendOnEveryTarget", "[simd]") {
  const EachTarget targets;
  for (const char* preset : {"default", "alpine", "badlands", "craters", "dunes", "island", "lake",
                             "lava", "plain", "planet", "sunset"}) {
    const Scene scene = resolve_scene(
        preset, {"viewport.width=203", "viewport.height=131", "grid.width=90", "grid.height=77"});
    const SceneResources resources = load_scene_resources(scene);
    const Frame reference = render_frame(scene, resources, all_outputs(Backend::kReference));
    for (const std::string& target : targets.runnable()) {
      simd::force_target(target);
      INFO(preset << " on " << target);
      require_same_frames(render_frame(scene, resources, all_outputs(Backend::kSimd)), reference);
    }
  }
}

TEST_CASE("simdFramesMatchTheReferenceWithEverySkipOffAndAtOddSizes", "[simd]") {
  const EachTarget targets;
  FrameSkips none;
  none.invalid_vertices = none.unseen_vertices = none.unused_octaves = none.empty_tiles = false;
  none.water = none.fog = none.dither = none.specular = none.zero_weights = false;
  for (const auto& [preset, overrides] :
       std::vector<std::pair<const char*, std::vector<std::string>>>{
           {"alpine", {"shading.triplanar=false", "viewport.width=131", "viewport.height=67"}},
           {"lake", {"camera.pitch_deg=-35", "viewport.width=100", "viewport.height=71"}},
           {"default", {"camera.pitch_deg=12", "viewport.width=97", "viewport.height=65"}},
           {"dunes", {"shading.texture_filter=\"bilinear\"", "viewport.width=90"}},
           // Gradient shading: the vertices' light (stage 5), its resolve and the gradient.
           {"default", {"shading.mode=\"gradient\"", "lighting.shadows=true"}},
           {"lake", {"shading.mode=\"gradient\"", "shading.gradient.range=[-30, 300]"}},
           {"planet", {"shading.mode=\"gradient\"", "viewport.width=96"}},
           // The planet's background and water (core/planet_shading.h): near the surface
           // looking at the horizon (the water sphere, the datum's fog, the sky from the
           // limb), below the datum (the plane's rule), without water or fog.
           {"planet", {"camera.position=[0, 700, 0]", "camera.pitch_deg=1", "viewport.width=96"}},
           {"planet", {"camera.position=[0, -10, 0]", "camera.pitch_deg=8", "viewport.width=96"}},
           {"planet", {"terrain.water_level=null", "sky.fog_density=0", "viewport.width=96"}},
           // Rays along the axis through the camera, down and up: the centre pixel of an odd
           // image looks along `forward`, whose horizontal length is cos(pi/2) ~ 6e-17, not 0
           // (the exact-0 fallbacks of the sky's azimuth and the footprint are unreachable
           // from a camera), so these reach the near-vertical rays, not the fallbacks.
           {"planet", {"camera.pitch_deg=-90", "viewport.width=33", "viewport.height=33"}},
           {"planet",
            {"camera.position=[0, 700, 0]", "camera.pitch_deg=90", "viewport.width=33",
             "viewport.height=33"}},
           // The atmosphere at its ends (core/atmosphere.h's domains): the sun at the zenith,
           // set, the camera in space, below height 0 in thin air, every coefficient at its
           // maximum (every column capped).
           {"default", {"sky.atmosphere={}", "lighting.sun_elevation_deg=90", "viewport.width=80"}},
           {"default",
            {"sky.atmosphere={}", "lighting.sun_elevation_deg=-30", "viewport.width=80"}},
           {"default", {"sky.atmosphere={}", "camera.position=[0, 1e6, 0]", "viewport.width=80"}},
           {"lake",
            {"sky.atmosphere.scale_height=10", "camera.position=[0, -50, 0]", "viewport.width=80"}},
           {"lake",
            {"sky.atmosphere.mie=0.01", "sky.atmosphere.rayleigh=[0.01, 0.01, 0.01]",
             "sky.atmosphere.mie_g=0.95", "sky.atmosphere.intensity=1000", "viewport.width=80"}}}) {
    std::vector<std::string> all = {"grid.width=61", "grid.height=53"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    const Scene scene = resolve_scene(preset, all);
    const SceneResources resources = load_scene_resources(scene);
    for (const bool skips : {true, false}) {
      FrameRequest reference_request = all_outputs(Backend::kReference);
      FrameRequest simd_request = all_outputs(Backend::kSimd);
      if (!skips) {
        reference_request.skips = simd_request.skips = none;
      }
      const Frame reference = render_frame(scene, resources, reference_request);
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        INFO(preset << " on " << target << (skips ? "" : ", every skip off"));
        require_same_frames(render_frame(scene, resources, simd_request), reference);
      }
    }
  }
}

TEST_CASE("simdFramesAreBitIdenticalForOneTwoAndEightThreads", "[simd]") {
  // lava, and with cast shadows (their cache's rows are split among the threads too).
  for (const char* shadows : {"lighting.shadows=false", "lighting.shadows=true"}) {
    const Scene scene = resolve_scene("lava", {"viewport.width=256", "viewport.height=192",
                                               "grid.width=128", "grid.height=128", shadows});
    const SceneResources resources = load_scene_resources(scene);
    std::vector<Frame> frames;
    for (const std::size_t threads : {1, 2, 8}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      frames.push_back(render_frame(scene, resources, all_outputs(Backend::kSimd)));
    }
    INFO(shadows);
    require_same_frames(frames[1], frames[0]);
    require_same_frames(frames[2], frames[0]);
  }
}

}  // namespace
}  // namespace relief
