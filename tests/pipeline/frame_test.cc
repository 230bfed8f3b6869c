// The frame as the library runs it: the stage table over a backend, the tile-fused back end,
// the double backend and the per-pixel outputs a caller can ask for.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "pipeline/stage_table.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

const std::vector<std::string> kSmall = {"viewport.width=150", "viewport.height=110",
                                         "grid.width=80", "grid.height=80"};

FrameRequest with_all_outputs(Backend backend = Backend::kReference) {
  FrameRequest request;
  request.backend = backend;
  request.outputs = {true, true, true, true, true, true};
  return request;
}

TEST_CASE("tileFusedFramesEqualTheStagesRunOverTheWholeFrameBitForBit", "[frame]") {
  // The fused back end (raster, resolve, shade, encode per 64 x 64 tile) must reproduce the
  // stage functions composed over full-size buffers: the image and the linear radiance, for
  // every preset, for 1 and 3 threads, and for a viewport that is no multiple of the tile size.
  for (const std::string& preset : preset_names()) {
    const Scene scene = resolve_scene(preset, kSmall);
    const SceneResources resources = load_scene_resources(scene);
    const FrameImage whole = render_whole_frame(scene, resources);
    for (int threads : {1, 3}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      FrameRequest request;
      request.outputs.linear = true;
      const Frame fused = render_frame(scene, resources, request);
      INFO(preset << ", " << threads << " threads");
      CHECK(fused.image.srgb == whole.srgb);
      CHECK(fused.image.linear == whole.linear);
    }
  }
}

TEST_CASE("requestedOutputsAreThoseOfTheStagesAndNothingElseIsAllocated", "[frame]") {
  const Scene scene = resolve_scene("lake", kSmall);
  const SceneResources resources = load_scene_resources(scene);
  const Frame plain = render_frame(scene, resources, FrameRequest{});
  CHECK(plain.image.srgb.size() == 150u * 110u * 3u);
  CHECK(plain.image.linear.empty());
  CHECK(plain.image.depth.empty());
  CHECK(plain.image.primitive.empty());
  CHECK(plain.image.normal.empty());
  CHECK(plain.image.world_height.empty());
  CHECK(plain.image.octaves.empty());

  const Frame frame = render_frame(scene, resources, with_all_outputs());
  const FrameImage& image = frame.image;
  CHECK(image.srgb == plain.image.srgb);
  const TerrainFrame terrain = rasterize_terrain(scene, resources);
  const raster::ResolvedFrame resolved = resolve_for_shading(terrain);
  const double camera_y = scene.camera.position[1];
  const float nu_max = float(scene.terrain.last_octave - scene.terrain.first_octave + 1);
  int covered = 0;
  for (std::size_t k = 0; k < image.primitive.size(); ++k) {
    // Visibility: the whole-frame rasteriser's ids and depths exactly.
    REQUIRE(image.primitive[k] == terrain.visibility.primitive[k]);
    REQUIRE(image.depth[k] == terrain.visibility.depth[k]);
    if (image.primitive[k] == raster::kNoPrimitive) {
      REQUIRE(image.world_height[k] == 0.0f);
      continue;
    }
    ++covered;
    const double nx = image.normal[3 * k], ny = image.normal[3 * k + 1],
                 nz = image.normal[3 * k + 2];
    REQUIRE(std::abs(nx * nx + ny * ny + nz * nz - 1.0) < 1e-5);
    REQUIRE(ny > 0.0);
    // World height: camera y plus the resolved camera-relative height, rounded once.
    REQUIRE(image.world_height[k] == static_cast<float>(camera_y + resolved.value[2][k]));
    REQUIRE(image.octaves[k] >= 1.0f);
    REQUIRE(image.octaves[k] <= nu_max);
  }
  CHECK(covered > 150 * 110 / 4);
}

TEST_CASE("theDoubleBackendRendersTheSameFrameToFloatPrecision", "[frame]") {
  for (const std::string& preset : {std::string("default"), std::string("lava")}) {
    const Scene scene = resolve_scene(preset, kSmall);
    const SceneResources resources = load_scene_resources(scene);
    const Frame f = render_frame(scene, resources, with_all_outputs(Backend::kReference));
    const Frame d = render_frame(scene, resources, with_all_outputs(Backend::kReferenceDouble));
    INFO(preset);
    REQUIRE(d.image.linear.size() == f.image.linear.size());
    std::size_t same_primitive = 0, bytes_differing = 0;
    double worst_height = 0;
    for (std::size_t k = 0; k < f.image.primitive.size(); ++k) {
      same_primitive += f.image.primitive[k] == d.image.primitive[k];
      if (f.image.primitive[k] == d.image.primitive[k] &&
          f.image.primitive[k] != raster::kNoPrimitive) {
        worst_height = std::max(
            worst_height, double(std::abs(f.image.world_height[k] - d.image.world_height[k])));
      }
    }
    for (std::size_t k = 0; k < f.image.srgb.size(); ++k) {
      REQUIRE(std::isfinite(d.image.linear[k]));
      bytes_differing += std::abs(int(f.image.srgb[k]) - int(d.image.srgb[k])) > 2;
    }
    // Coverage moves only where a float vertex rounds across a pixel centre; heights agree to
    // the float error of stage 3 (docs: 0.02 units at most on the default frame), except on a
    // silhouette, where a triangle seen edge-on turns a vertex's rounding into a larger move
    // across it (measured: 0.13 on the default frame).
    CHECK(same_primitive > f.image.primitive.size() * 95 / 100);
    CHECK(worst_height < 0.2);
    CHECK(bytes_differing < f.image.srgb.size() / 50);
  }
}

TEST_CASE("theStageTableListsEveryStageOnceInFrameOrder", "[frame]") {
  static_assert(kFrameStageCount == 14);
  for (std::size_t k = 0; k < kFrameStageCount; ++k) {
    CHECK(static_cast<std::size_t>(kFrameStages[k].id) == k);
    CHECK(kFrameStages[k].grain > 0);
  }
  const Scene scene = resolve_scene("default", kSmall);
  const SceneResources resources = load_scene_resources(scene);
  const Frame frame = render_frame(scene, resources, FrameRequest{});
  REQUIRE(frame.stats.stages.size() == kFrameStageCount + 1);  // the plan, then the table
  for (std::size_t k = 0; k < kFrameStageCount; ++k) {
    CHECK(frame.stats.stages[k + 1].name == kFrameStages[k].name);
  }
  CHECK(frame.stats.tile_parts.size() == 5);
  CHECK(frame.stats.raster.setup > 0);
}

TEST_CASE("backendNamesRoundTrip", "[frame]") {
  for (std::string_view name : backend_names()) {
    REQUIRE(backend_from_name(name).has_value());
    CHECK(backend_name(*backend_from_name(name)) == name);
  }
  CHECK(backend_names().size() == 4);
  CHECK(backend_from_name("gl") == Backend::kGl);
  CHECK_FALSE(backend_from_name("vulkan").has_value());
  CHECK_FALSE(backend_from_name("Reference").has_value());
}

// Resources depend on the terrain and shading settings alone: every other field keeps them (the
// Python module's Scene.set relies on it), and a field of either, its value changed, does not;
// each verdict checked against what load_scene_resources loads.
TEST_CASE("sameResourceInputsMeansTheSameLoadedResources", "[frame]") {
  const Scene base = resolve_scene("default", {"shading.texture_size=16"});
  const SceneResources loaded = load_scene_resources(base);
  for (const auto& [assignment, same] :
       std::vector<std::pair<std::string, bool>>{{"camera.yaw_deg=50", true},
                                                 {"viewport.width=77", true},
                                                 {"lighting.sun_elevation_deg=3", true},
                                                 {"grid.width=40", true},
                                                 {"output.image=\"x.png\"", true},
                                                 {"terrain.seed=8", false},
                                                 {"terrain.lattice_size=128", false},
                                                 {"shading.texture_size=32", false},
                                                 {"shading.mip_blend=0.5", false}}) {
    INFO(assignment);
    const Scene changed = resolve_scene("default", {"shading.texture_size=16", assignment});
    CHECK(same_resource_inputs(base, changed) == same);
    const SceneResources other = load_scene_resources(changed);
    bool equal = other.lattice.values == loaded.lattice.values &&
                 other.textures.size() == loaded.textures.size();
    for (std::size_t k = 0; equal && k < loaded.textures.size(); ++k) {
      equal = other.textures[k].texels == loaded.textures[k].texels;
    }
    CHECK(equal == same);
  }
}

}  // namespace
}  // namespace relief
