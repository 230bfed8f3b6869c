// terrain.sketch's image (§3's low-frequency base, core/height_sketch.h): a grey PNG of 8 or
// 16 bits, from a file or built in, checked as the layer textures are (png_checks.h) before
// stb_image decodes it; or terrain.heightfield's file (heightfield_files.h).
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/png_header.h"
#include "pipeline/builtin_sketches.h"
#include "pipeline/heightfield_files.h"
#include "pipeline/png_checks.h"
#include "pipeline/scene_resources.h"

namespace relief {

namespace {

// Refuses a sketch from its header: one grey channel of 8 or 16 bits, 2 to kMaxSketchSize
// texels on a side.
void check_sketch_header(const std::vector<unsigned char>& bytes, const std::string& field,
                         const std::string& path) {
  const PngHeader png = png_header_or_throw(bytes, field, path);
  if (png.colour_type != 0) {
    static constexpr const char* kTypes[] = {"grey",         "?", "RGB", "palette",
                                             "grey + alpha", "?", "RGBA"};
    const char* type = png.colour_type <= 6 ? kTypes[png.colour_type] : "unknown";
    throw SceneError(path, "scene: " + field + " has colour type " +
                               std::to_string(png.colour_type) + " (" + type +
                               "); allowed: a grey PNG with one channel (colour type 0)");
  }
  if (png.bit_depth != 8 && png.bit_depth != 16) {
    throw SceneError(path, "scene: " + field + " has " + std::to_string(png.bit_depth) +
                               " bits per channel; allowed: 8 or 16");
  }
  const std::uint32_t lo = limits::kMinSketchSize, hi = limits::kMaxSketchSize;
  if (png.width < lo || png.width > hi || png.height < lo || png.height > hi) {
    throw SceneError(path, "scene: " + field + " is " + std::to_string(png.width) + "x" +
                               std::to_string(png.height) + " texels; allowed " +
                               std::to_string(lo) + " to " + std::to_string(hi) + " on each side");
  }
}

}  // namespace

std::optional<HeightSketch> load_height_sketch(const Scene& scene) {
  if (scene.terrain.heightfield) {
    return load_height_field(*scene.terrain.heightfield);  // heightfield_files.h
  }
  if (!scene.terrain.sketch) {
    return std::nullopt;
  }
  const SketchSettings& settings = *scene.terrain.sketch;
  const std::string path = "terrain.sketch.image";
  const std::string field = path + " = \"" + brief_text(settings.image) + "\"";
  std::vector<unsigned char> bytes;
  static constexpr std::string_view kBuiltin = "builtin:";
  if (settings.image.rfind(kBuiltin, 0) == 0) {
    const std::string_view name = std::string_view(settings.image).substr(kBuiltin.size());
    const std::vector<std::string_view> names = builtin_sketch_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string allowed;
      for (const std::string_view sketch : names) {
        allowed += "builtin:" + std::string(sketch) + ", ";
      }
      throw SceneError(path, "scene: " + field + " names no built-in sketch; allowed: " + allowed +
                                 "or a PNG file (the builtin:basis/ images are " +
                                 "terrain.basis's, not sketches)");
    }
    const std::span<const unsigned char> png = builtin_sketch_png(name);
    bytes.assign(png.begin(), png.end());
    check_sketch_header(bytes, field, path);
  } else {
    bytes =
        read_png_file(settings.image, field, path, [&](const std::vector<unsigned char>& header) {
          check_sketch_header(header, field, path);
        });
  }
  // 16-bit samples whatever the file's depth (stb scales 8-bit values by 257, so v / 65535 is
  // v8 / 255 exactly); the size, the chunks and the inflated size checked before stb sees the
  // file (png_checks.h).
  const Grey16Image grey = decode_grey16_png(bytes, field, path);
  return make_height_sketch(settings, grey.width, grey.height, grey.levels, 65535);
}

}  // namespace relief
