// The built-in scene presets: the files of scenes/ compiled into the binary (the build
// generates scene_presets.cc from them), so presets work from any directory.
#pragma once

#include <span>
#include <string_view>

namespace relief {

struct ScenePreset {
  std::string_view name;  // file name without .json
  std::string_view json;  // the file's text: a layer over the defaults
};

std::span<const ScenePreset> scene_presets();

}  // namespace relief
