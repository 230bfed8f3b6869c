// The presets the GL backend draws: every preset but those with what it has no GLSL twin of
// yet (cast shadows, sky light, terrain reflections, a GeoMipMap mesh: pipeline/gl_backend.h,
// gl_missing_feature), which it refuses (tested in gl_refusals_test.cc).
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene_json.h"
#include "pipeline/gl_backend.h"

namespace relief::test {

inline std::vector<std::string> gl_preset_names() {
  std::vector<std::string> names;
  for (const std::string& preset : preset_names()) {
    if (gl_missing_feature(resolve_scene(preset, {})).empty()) {
      names.push_back(preset);
    }
  }
  return names;
}

}  // namespace relief::test
