#include "tools/scene_resources.h"

#include <bit>
#include <fstream>
#include <iterator>
#include <string>

#include <stb_image.h>

#include "core/limits.h"
#include "core/scene_json.h"
#include "core/srgb.h"
#include "core/texture_synthesis.h"

namespace relief {

RgbImage load_layer_texture(const MaterialLayer& layer, int builtin_size, const std::string& path) {
  static constexpr std::string_view kBuiltin = "builtin:";
  if (layer.texture.rfind(kBuiltin, 0) == 0) {
    return synthesize_texture(std::string_view(layer.texture).substr(kBuiltin.size()),
                              builtin_size);
  }
  std::ifstream file(layer.texture, std::ios::binary);
  if (!file) {
    throw SceneError(path, "scene: " + path + " = \"" + layer.texture + "\" cannot be opened");
  }
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                         std::istreambuf_iterator<char>());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height,
                             &channels) ||
      bytes.size() < 8 || bytes[1] != 'P' || bytes[2] != 'N' || bytes[3] != 'G') {
    throw SceneError(path, "scene: " + path + " = \"" + layer.texture + "\" is not a PNG image");
  }
  if (width != height || width < limits::kMinTextureSize || width > limits::kMaxTextureSize ||
      !std::has_single_bit(static_cast<unsigned>(width)) ||
      stbi_is_16_bit_from_memory(bytes.data(), int(bytes.size()))) {
    throw SceneError(path, "scene: " + path + " = \"" + layer.texture + "\" is " +
                               std::to_string(width) + "x" + std::to_string(height) +
                               " pixels; allowed: square 8-bit images with a power-of-two side "
                               "from 4 to 4096");
  }
  unsigned char* pixels = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()),
                                                &width, &height, &channels, 3);
  if (!pixels) {
    throw SceneError(path, "scene: " + path + " = \"" + layer.texture +
                               "\" could not be decoded: " + stbi_failure_reason());
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
  return resources;
}

}  // namespace relief
