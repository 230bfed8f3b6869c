// The helpers of the scene-limit tests (tests/core/scene_limits_test.cc, the refusals and the
// derivations; tests/core/scene_limits_frame_test.cc, frames at the bounds and the issue's
// cases): scenes resolved with overrides, their messages, and what a small frame shows.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "raster/resolve.h"
#include "tests/oracles/whole_frame.h"

namespace relief::test::scene_limits {

// A small frame: whole-frame checks for a hundred scenes stay fast under sanitizers.
inline const std::vector<std::string> kSmallFrame = {"viewport.width=64", "viewport.height=48",
                                                     "grid.width=32", "grid.height=32"};

inline double below(double x) {
  return std::nextafter(x, -std::numeric_limits<double>::infinity());
}

inline double above(double x) {
  return std::nextafter(x, std::numeric_limits<double>::infinity());
}

// The message of the SceneError that resolving the default scene with `overrides` throws, or
// "" when the scene is accepted.
inline std::string error_of(const std::vector<std::string>& overrides) {
  try {
    resolve_scene("default", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// "a + b + ..." without operator+ on literals (GCC 12 warns falsely about it, bug 105651).
inline std::string cat(std::initializer_list<std::string> parts) {
  std::string out;
  for (const std::string& part : parts) {
    out.append(part);
  }
  return out;
}

// What a frame at a bound must show.
struct FrameCheck {
  std::size_t pixels = 0;
  std::size_t covered = 0;
  std::size_t bad_radiance = 0;  // NaN, infinite or negative
  std::size_t bad_buffers = 0;   // NaN or infinite entries of any stage buffer
  std::vector<float> heights;    // of the valid vertices
  std::vector<float> nu;         // of the valid vertices
};

template <class Values>
inline std::size_t non_finite(const Values& values) {
  return static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }));
}

// Resources (lattice, synthesised textures) are the expensive part of a small frame: built
// once per distinct set of the fields they depend on.
inline const SceneResources& resources_for(const Scene& scene) {
  static std::map<std::string, SceneResources> cache;
  std::string key = cat(
      {std::to_string(scene.terrain.seed), "/", std::to_string(scene.terrain.lattice_size), "/",
       std::to_string(scene.shading.texture_size), "/", format_number(scene.shading.mip_blend)});
  for (const MaterialLayer& layer : scene.shading.layers) {
    key.append("/").append(layer.texture);
  }
  auto it = cache.find(key);
  if (it == cache.end()) {
    it = cache.emplace(key, load_scene_resources(scene)).first;
  }
  return it->second;
}

inline FrameCheck render_scene(const Scene& scene) {
  const SceneResources& resources = resources_for(scene);
  FrameRequest request;
  request.outputs.linear = true;
  const FrameImage image = render_frame(scene, resources, request).image;
  const TerrainFrame terrain = rasterize_terrain(scene, resources);
  const raster::ResolvedFrame resolved = resolve_for_shading(terrain);
  FrameCheck f;
  f.pixels = terrain.visibility.primitive.size();
  for (std::uint32_t p : terrain.visibility.primitive) {
    f.covered += p != raster::kNoPrimitive;
  }
  f.bad_radiance =
      static_cast<std::size_t>(std::count_if(image.linear.begin(), image.linear.end(),
                                             [](float v) { return !(v >= 0.0f && v <= 3e38f); }));
  const GridBuffers<float>& g = terrain.grid;
  for (const auto* buffer :
       {&g.dx, &g.dz, &g.sigma, &g.nu, &g.height, &g.nx, &g.ny, &g.nz, &g.slope, &g.water_depth,
        &terrain.clip_x, &terrain.clip_y, &terrain.clip_z, &terrain.clip_w}) {
    f.bad_buffers += non_finite(*buffer);
  }
  for (const auto* streams : {&resolved.value, &resolved.ddx, &resolved.ddy}) {
    for (const auto& stream : *streams) {
      f.bad_buffers += non_finite(stream);
    }
  }
  for (std::size_t k = 0; k < g.valid.size(); ++k) {
    if (g.valid[k]) {
      f.heights.push_back(g.height[k]);
      f.nu.push_back(g.nu[k]);
    }
  }
  return f;
}

inline FrameCheck render_small(const std::vector<std::string>& overrides) {
  std::vector<std::string> set = kSmallFrame;
  set.insert(set.end(), overrides.begin(), overrides.end());
  return render_scene(resolve_scene("default", set));
}

}  // namespace relief::test::scene_limits
