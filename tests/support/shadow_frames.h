// The small frames the cast-shadow and sky-light tests render (core/sun_horizons.h,
// core/sky_horizons.h): a scene's overrides shrunk to a frame of a few milliseconds with the
// smallest horizon cache, and its linear radiance and primitive ids from the reference backend.
#pragma once

#include <string>
#include <vector>

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

inline Frame render_reference_linear(const Scene& scene) {
  FrameRequest request;
  request.backend = Backend::kReference;
  request.outputs.linear = true;
  request.outputs.primitive = true;
  return render_frame(scene, load_scene_resources(scene), request);
}

}  // namespace relief::test
