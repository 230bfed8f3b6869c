// The small frames the cast-shadow and sky-light tests render (core/sun_horizons.h,
// core/sky_horizons.h): a scene's overrides shrunk to a frame of a few milliseconds with the
// smallest horizon cache, and its linear radiance and primitive ids from the reference backend.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"

namespace relief::test {

// `more`, then 200 x 150 pixels from a 128^2 grid and a cache of 128 samples a side.
inline std::vector<std::string> small_shadow_frame(std::vector<std::string> more) {
  more.insert(more.end(), {"viewport.width=200", "viewport.height=150", "grid.width=128",
                           "grid.height=128", "lighting.shadow_resolution=128"});
  return more;
}

// `request` (the linear output added) rendered, every linear value required finite: the
// reference a bit-identity test compares the simd backend's frames with.
inline Frame render_finite(const Scene& scene, const SceneResources& resources,
                           FrameRequest& request) {
  request.outputs.linear = true;
  Frame frame = render_frame(scene, resources, request);
  for (const float value : frame.image.linear) {
    REQUIRE(std::isfinite(value));
  }
  return frame;
}

inline Frame render_reference_linear(const Scene& scene) {
  FrameRequest request;
  request.backend = Backend::kReference;
  request.outputs.linear = true;
  request.outputs.primitive = true;
  return render_frame(scene, load_scene_resources(scene), request);
}

}  // namespace relief::test
