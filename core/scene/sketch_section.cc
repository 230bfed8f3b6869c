// terrain.sketch (§3's low-frequency base, core/height_sketch.h): the field's strict reading.
#include <filesystem>
#include <optional>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"

namespace relief {

// A file name relative to the scene file's directory (the current one for --set), made
// absolute so that the printed scene loads back from anywhere; "builtin:..." and absolute
// names unchanged.
std::string resolve_scene_path(std::string name, const std::filesystem::path& base_dir) {
  if (name.rfind("builtin:", 0) == 0 || !std::filesystem::path(name).is_relative()) {
    return name;
  }
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(base_dir / name, ec);
  return ec ? (base_dir / name).lexically_normal().string() : absolute.lexically_normal().string();
}

// terrain.sketch: null removes it; an object patches it (a new one must name its image).
// Whether the image can be read is checked when it is loaded (pipeline/scene_resources.h).
void apply_sketch(const LayerReader& in, const json& value, const std::string& path,
                  std::optional<SketchSettings>& sketch, const std::filesystem::path& base_dir) {
  if (value.is_null()) {
    sketch.reset();
    return;
  }
  if (!sketch && value.is_object() && !value.contains("image")) {
    in.fail(path, path + " must be null or an object with at least an \"image\"");
  }
  SketchSettings s = sketch.value_or(SketchSettings{});
  const Range coordinate{-limits::kMaxCameraCoordinate, limits::kMaxCameraCoordinate};
  const Range height{-limits::kMaxBaseHeight, limits::kMaxBaseHeight};
  in.object(
      value, path,
      Handlers{
          {"image",
           [&](const json& v, const std::string& p) {
             s.image = resolve_scene_path(in.string(v, p), base_dir);
           }},
          {"extent",
           [&](const json& v, const std::string& p) {
             s.extent = in.vector<4>(v, p, coordinate);
             const auto& e = s.extent;
             if (!(e[2] - e[0] >= limits::kMinSketchSpan &&
                   e[3] - e[1] >= limits::kMinSketchSpan)) {
               in.fail(p, p + " = " + brief(v) +
                              " is empty or too thin; allowed [x0, z0, x1, z1] with x1 - x0 "
                              "and z1 - z0 at least " +
                              format_number(limits::kMinSketchSpan));
             }
           }},
          {"height",
           [&](const json& v, const std::string& p) {
             s.height = in.vector<2>(v, p, height);
             if (!(s.height[0] < s.height[1])) {
               in.fail(p, p + " = " + brief(v) + " is empty; allowed [low, high] with low < high");
             }
           }},
      });
  sketch = s;
}

}  // namespace relief
