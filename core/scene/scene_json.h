// Scene files: loading, strict validation and printing (docs/scene-reference.md).
//
// A scene is built in layers: the built-in defaults, then a preset or a scene file, then each
// --set override in command-line order. Every layer is a (partial) scene in JSON and goes
// through the same checks: unknown keys, wrong types, non-finite numbers and values out of
// range are rejected with the JSON path, the value and the allowed range. Cross-field rules
// are checked once all layers are applied. Nothing is clamped or ignored silently.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"

namespace relief {

// Bad scene input. what() is the whole message; path() the JSON path ("terrain.r") or "" when
// the problem is not one field (a file that is not JSON, an unknown preset).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string path, const std::string& message)
      : std::runtime_error(message), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Applies one layer onto `scene`. `source` says where the layer came from ("scene file
// a.json", "--set terrain.H=2") and starts every message; relative texture paths are taken
// relative to `base_dir` (a scene file's directory). Throws SceneError.
void apply_scene_layer(Scene& scene, const nlohmann::json& layer, std::string_view source,
                       const std::filesystem::path& base_dir = {});

// Cross-field rules (octave range, grid versus margin, near versus far, field of view versus
// aspect). Throws SceneError.
void validate_scene(const Scene& scene);

// The effective scene, every field present; loading it back gives the same scene.
nlohmann::json scene_to_json(const Scene& scene);

// scene_to_json as text, exactly what `relief scene` prints: two-space indentation, UTF-8 as
// it is (invalid bytes replaced), ending in a newline. Images carry it too (image_metadata.h).
std::string scene_json_text(const Scene& scene);

// "terrain.H=0.85" as a one-field layer. VALUE is read as JSON when it parses (numbers,
// true, null, [1, 2, 3], "quoted") and as a plain string otherwise (quintic).
nlohmann::json parse_override(std::string_view assignment);

// Built-in presets (scenes/*.json, compiled in) by name; "default" is the defaults alone.
std::vector<std::string> preset_names();
bool is_preset(std::string_view name);

// Defaults, then the preset or JSON file named by `scene_arg` (empty: "default"), then the
// overrides, then validate_scene. Throws SceneError for any bad input, with a message that
// names the field.
Scene resolve_scene(std::string_view scene_arg, const std::vector<std::string>& overrides);

// resolve_scene for a scene file already in memory: `text` is the file's bytes, `file_name`
// names it in messages ("scene file NAME: ...") and relative texture paths are taken relative
// to `base_dir`. resolve_scene reads a file and calls this; the fuzzers (fuzz/) call it
// directly. Throws SceneError for any bad input.
Scene resolve_scene_text(std::string_view text, std::string_view file_name,
                         const std::filesystem::path& base_dir,
                         const std::vector<std::string>& overrides);

}  // namespace relief
