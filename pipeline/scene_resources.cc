#include "pipeline/scene_resources.h"

#include <bit>
#include <optional>
#include <string>
#include <vector>

#include <stb_image.h>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "core/texture_synthesis.h"
#include "pipeline/builtin_sketches.h"
#include "pipeline/png_header.h"

namespace relief {

namespace {

// Refuses, from its first bytes alone, a file that is no PNG or a PNG Relief cannot use.
void check_texture_header(const std::vector<unsigned char>& bytes, const std::string& field,
                          const std::string& path) {
  const std::optional<PngHeader> png = parse_png_header(bytes.data(), bytes.size());
  if (!png) {
    throw SceneError(path, "scene: " + field + " is not a PNG image (no PNG signature and header)");
  }
  const std::uint32_t side = png->width;
  if (png->width != png->height || side < std::uint32_t(limits::kMinTextureSize) ||
      side > std::uint32_t(limits::kMaxTextureSize) || !std::has_single_bit(side)) {
    throw SceneError(path, "scene: " + field + " is " + std::to_string(png->width) + "x" +
                               std::to_string(png->height) +
                               " pixels; allowed: square, a power of two from " +
                               std::to_string(limits::kMinTextureSize) + " to " +
                               std::to_string(limits::kMaxTextureSize));
  }
  if (png->bit_depth > 8) {
    throw SceneError(path, "scene: " + field + " has " + std::to_string(png->bit_depth) +
                               " bits per channel; allowed: 8-bit PNG");
  }
}

// Refuses a sketch from its header: one grey channel of 8 or 16 bits, 2 to kMaxSketchSize
// texels on a side.
void check_sketch_header(const std::vector<unsigned char>& bytes, const std::string& field,
                         const std::string& path) {
  const std::optional<PngHeader> png = parse_png_header(bytes.data(), bytes.size());
  if (!png) {
    throw SceneError(path, "scene: " + field + " is not a PNG image (no PNG signature and header)");
  }
  if (png->colour_type != 0) {
    static constexpr const char* kTypes[] = {"grey",         "?", "RGB", "palette",
                                             "grey + alpha", "?", "RGBA"};
    const char* type = png->colour_type <= 6 ? kTypes[png->colour_type] : "unknown";
    throw SceneError(path, "scene: " + field + " has colour type " +
                               std::to_string(png->colour_type) + " (" + type +
                               "); allowed: a grey PNG with one channel (colour type 0)");
  }
  if (png->bit_depth != 8 && png->bit_depth != 16) {
    throw SceneError(path, "scene: " + field + " has " + std::to_string(png->bit_depth) +
                               " bits per channel; allowed: 8 or 16");
  }
  const std::uint32_t lo = limits::kMinSketchSize, hi = limits::kMaxSketchSize;
  if (png->width < lo || png->width > hi || png->height < lo || png->height > hi) {
    throw SceneError(path, "scene: " + field + " is " + std::to_string(png->width) + "x" +
                               std::to_string(png->height) + " texels; allowed " +
                               std::to_string(lo) + " to " + std::to_string(hi) + " on each side");
  }
}

}  // namespace

std::optional<HeightSketch> load_height_sketch(const Scene& scene) {
  if (!scene.terrain.sketch) {
    return std::nullopt;
  }
  const SketchSettings& settings = *scene.terrain.sketch;
  const std::string path = "terrain.sketch.image";
  const std::string field = path + " = \"" + brief_text(settings.image) + "\"";
  std::vector<unsigned char> bytes;
  static constexpr std::string_view kBuiltin = "builtin:";
  if (settings.image.rfind(kBuiltin, 0) == 0) {
    const std::span<const unsigned char> png =
        builtin_sketch_png(std::string_view(settings.image).substr(kBuiltin.size()));
    if (png.empty()) {
      throw SceneError(path, "scene: " + field + " names no built-in sketch; allowed: " +
                                 "builtin:island, or a PNG file");
    }
    bytes.assign(png.begin(), png.end());
    check_sketch_header(bytes, field, path);
  } else {
    try {
      InputFile file(settings.image, limits::kMaxTextureFileBytes);
      bytes.resize(kPngHeaderBytes);
      bytes.resize(file.read(bytes.data(), bytes.size()));
      check_sketch_header(bytes, field, path);
      const std::string rest = file.read_rest();
      bytes.insert(bytes.end(), rest.begin(), rest.end());
    } catch (const InputFileError& e) {
      throw SceneError(path, "scene: " + field + " " + e.what());
    }
  }
  // 16-bit samples whatever the file's depth (stb scales 8-bit values by 257, so v / 65535 is
  // v8 / 255 exactly).
  int width = 0, height = 0, channels = 0;
  stbi_us* grey = stbi_load_16_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width,
                                           &height, &channels, 1);
  const std::optional<PngHeader> png = parse_png_header(bytes.data(), bytes.size());
  if (!grey || std::uint32_t(width) != png->width || std::uint32_t(height) != png->height) {
    stbi_image_free(grey);
    const char* reason = grey ? "its header and data disagree" : stbi_failure_reason();
    throw SceneError(path, "scene: " + field + " could not be decoded: " +
                               (reason && *reason ? reason : "corrupt image data"));
  }
  const HeightSketch sketch = make_height_sketch(
      settings, width, height,
      std::span<const std::uint16_t>(grey, std::size_t(width) * std::size_t(height)), 65535);
  stbi_image_free(grey);
  return sketch;
}

RgbImage load_layer_texture(const MaterialLayer& layer, int builtin_size, const std::string& path) {
  static constexpr std::string_view kBuiltin = "builtin:";
  if (layer.texture.rfind(kBuiltin, 0) == 0) {
    return synthesize_texture(std::string_view(layer.texture).substr(kBuiltin.size()),
                              builtin_size);
  }
  const std::string field = path + " = \"" + brief_text(layer.texture) + "\"";
  std::vector<unsigned char> bytes;
  try {
    InputFile file(layer.texture, limits::kMaxTextureFileBytes);
    bytes.resize(kPngHeaderBytes);
    bytes.resize(file.read(bytes.data(), bytes.size()));
    check_texture_header(bytes, field, path);
    const std::string rest = file.read_rest();
    bytes.insert(bytes.end(), rest.begin(), rest.end());
  } catch (const InputFileError& e) {
    throw SceneError(path, "scene: " + field + " " + e.what());
  }
  // stb takes an int size; kMaxTextureFileBytes keeps the file far below 2^31.
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()),
                                                &width, &height, &channels, 3);
  if (!pixels || width != height) {
    stbi_image_free(pixels);
    // stb leaves no reason for some corrupt streams (an invalid deflate block): never NULL here.
    const char* reason = pixels ? "its header and data disagree" : stbi_failure_reason();
    throw SceneError(path, "scene: " + field + " could not be decoded: " +
                               (reason && *reason ? reason : "corrupt image data"));
  }
  RgbImage image;
  image.size = width;
  image.rgb.resize(3 * std::size_t(width) * height);
  // PNG rows run top to bottom; texture v runs with world z, so the row order only mirrors
  // the pattern, which a tiling texture does not mind. sRGB-encoded bytes to linear albedo.
  for (std::size_t k = 0; k < image.rgb.size(); ++k) {
    image.rgb[k] = static_cast<float>(srgb_decode(pixels[k] / 255.0));
  }
  stbi_image_free(pixels);
  return image;
}

SceneResources load_scene_resources(const Scene& scene) {
  SceneResources resources;
  resources.lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  for (std::size_t k = 0; k < scene.shading.layers.size(); ++k) {
    const std::string path = "shading.layers[" + std::to_string(k) + "].texture";
    resources.textures.push_back(build_proto_texture(
        load_layer_texture(scene.shading.layers[k], scene.shading.texture_size, path),
        scene.shading.mip_blend));
  }
  resources.sketch = load_height_sketch(scene);
  return resources;
}

}  // namespace relief
