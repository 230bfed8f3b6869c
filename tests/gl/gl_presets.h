// The presets the GL backend draws: every preset but those with cast shadows, which have no
// GLSL twin yet and which the GL backend refuses (tested in gl_refusals_test.cc).
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene_json.h"

namespace relief::test {

inline std::vector<std::string> gl_preset_names() {
  std::vector<std::string> names;
  for (const std::string& preset : preset_names()) {
    if (!resolve_scene(preset, {}).lighting.shadows) {
      names.push_back(preset);
    }
  }
  return names;
}

}  // namespace relief::test
