#include "pipeline/scene_resources.h"

#include <atomic>
#include <bit>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <stb_image.h>
#include <tbb/parallel_for.h>

#include "core/basis_images.h"
#include "core/height_bounds.h"
#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "core/texture_synthesis.h"
#include "image/png_header.h"
#include "image/png_layout.h"
#include "pipeline/builtin_sketches.h"
#include "pipeline/parallel_rows.h"
#include "pipeline/png_checks.h"

namespace relief {

namespace {

// Refuses, from its first bytes alone, a file that is no PNG or a PNG Relief cannot use.
void check_texture_header(const std::vector<unsigned char>& bytes, const std::string& field,
                          const std::string& path, int max_side = limits::kMaxTextureSize) {
  const PngHeader png = png_header_or_throw(bytes, field, path);
  const std::uint32_t side = png.width;
  if (png.width != png.height || side < std::uint32_t(limits::kMinTextureSize) ||
      side > std::uint32_t(max_side) || !std::has_single_bit(side)) {
    throw SceneError(
        path, "scene: " + field + " is " + std::to_string(png.width) + "x" +
                  std::to_string(png.height) + " pixels; allowed: square, a power of two from " +
                  std::to_string(limits::kMinTextureSize) + " to " + std::to_string(max_side));
  }
  if (png.bit_depth > 8) {
    throw SceneError(path, "scene: " + field + " has " + std::to_string(png.bit_depth) +
                               " bits per channel; allowed: 8-bit PNG");
  }
}

// How messages name a layer's texture: `shading.layers[2].texture = "rock.png"`.
std::string texture_field(const MaterialLayer& layer, const std::string& path) {
  return path + " = \"" + brief_text(layer.texture) + "\"";
}

}  // namespace

RgbImage decode_texture_png(const std::vector<unsigned char>& png, const std::string& field,
                            const std::string& path) {
  check_texture_header(png, field, path);
  // stb takes an int size; kMaxTextureFileBytes keeps a file far below 2^31.
  if (png.size() > limits::kMaxTextureFileBytes) {
    throw SceneError(path, "scene: " + field + " has " + format_bytes(png.size()) +
                               "; allowed at most " + format_bytes(limits::kMaxTextureFileBytes));
  }
  check_png_image_data(png, field, path);
  int width = 0, height = 0, channels = 0;
  reset_stb_failure_reason();
  unsigned char* pixels = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &width,
                                                &height, &channels, 3);
  if (!pixels || width != height) {
    stbi_image_free(pixels);
    throw SceneError(path, "scene: " + field + " could not be decoded: " +
                               (pixels ? std::string("its header and data disagree")
                                       : stb_failure_reason_or("corrupt image data")));
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

RgbImage load_layer_texture(const MaterialLayer& layer, int builtin_size, const std::string& path) {
  static constexpr std::string_view kBuiltin = "builtin:";
  if (layer.texture.rfind(kBuiltin, 0) == 0) {
    return synthesize_texture(std::string_view(layer.texture).substr(kBuiltin.size()),
                              builtin_size);
  }
  const std::string field = texture_field(layer, path);
  const std::vector<unsigned char> bytes = read_png_file(
      layer.texture, field, path,
      [&](const std::vector<unsigned char>& header) { check_texture_header(header, field, path); });
  return decode_texture_png(bytes, field, path);
}

std::optional<Skybox> load_skybox(const Scene& scene) {
  if (!scene.sky.skybox) {
    return std::nullopt;
  }
  const SkyboxSettings& settings = *scene.sky.skybox;
  Skybox box;
  std::string first_field;
  for (std::size_t face = 0; face < settings.faces.size(); ++face) {
    const std::string path = "sky.skybox.faces[" + std::to_string(face) + "]";
    const std::string field = path + " = \"" + brief_text(settings.faces[face]) + "\"";
    const auto check_header = [&](const std::vector<unsigned char>& header) {
      check_texture_header(header, field, path, limits::kMaxSkyboxSize);
      const std::uint32_t side = png_header_or_throw(header, field, path).width;
      if (face > 0 && side != std::uint32_t(box.size)) {
        throw SceneError(path, "scene: " + field + " is " + std::to_string(side) + "x" +
                                   std::to_string(side) + " pixels, " + first_field + " is " +
                                   std::to_string(box.size) + "x" + std::to_string(box.size) +
                                   "; allowed: six faces of one size");
      }
    };
    const std::vector<unsigned char> bytes =
        read_png_file(settings.faces[face], field, path, check_header);
    const RgbImage image = decode_texture_png(bytes, field, path);
    if (face == 0) {
      box.size = image.size;
      first_field = field;
      box.texels.resize(settings.faces.size() * image.rgb.size());
    }
    // Rows as the file stores them, top first: t = 0 is a GL cube face's first row.
    float* out = box.texels.data() + face * image.rgb.size();
    for (std::size_t k = 0; k < image.rgb.size(); ++k) {
      out[k] = static_cast<float>(double(image.rgb[k]) * settings.intensity);
    }
  }
  return box;
}

namespace {

// §4.1: the bend maps elevation e to radius R + e, which must stay positive: terrain that can
// reach the planet's centre is refused (its bounds need the composed grid and the sketch, so
// this runs once they are loaded).
void check_planet_depth(const Scene& scene, const SceneResources& resources) {
  const TerrainSettings& t = scene.terrain;
  if (!t.planet || t.planet->radius == 0.0) {
    return;
  }
  const NoiseLattice& values = resources.terrain_values();
  const HeightBounds bounds =
      derive_height_bounds(values, stage3_terrain(t, values.size), resources.sketch_or_null());
  const double deepest = bounds.world_min - t.base_height;  // lowest elevation, radial
  if (!(t.planet->radius + deepest > 0.0)) {
    const std::string depth = format_number(-deepest);
    // The advice stays within the field's own range: past its maximum no radius holds.
    const std::string advice =
        -deepest < limits::kMaxPlanetRadius
            ? "allowed: a radius above that depth (terrain.planet.radius is at most " +
                  format_number(limits::kMaxPlanetRadius) + ")"
            : "no radius up to terrain.planet.radius's maximum " +
                  format_number(limits::kMaxPlanetRadius) +
                  " holds it: lower terrain.amplitude or the sketch's or height field's heights";
    throw SceneError(
        "terrain.planet.radius",
        "scene: terrain.planet.radius = " + format_number(t.planet->radius) +
            " is not above the depth the terrain can reach below the datum, " + depth +
            " (terrain.amplitude, the octaves' sum and the sketch's or height field's heights), so "
            "the surface would pass through the planet's centre; " +
            advice);
  }
}

}  // namespace

std::uint64_t ResourceSerial::next() noexcept {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;  // 0 names nothing
}

SceneResources load_scene_resources(const Scene& scene) {
  SceneResources resources;
  resources.lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  // The layers' textures are independent: built side by side (each one's bits are its own
  // inputs'), and a failure reported as the first failing layer's whatever the threads' order
  // (every layer is read first: peak memory stays within estimate_scene_resources_memory,
  // which counts them all). The other resources follow one by one: built beside the layers
  // (tbb::parallel_invoke) they saved no measurable time, and LeakSanitizer's exit check then
  // crashed in every process that had loaded OpenImageIO.
  // Gradient shading (shading.mode = gradient) samples no proto-texture: none is read or
  // synthesised, and a frame's set-up skips their cost (the layers still weigh the export's
  // splat maps, which read no texel).
  const std::size_t layers =
      scene.shading.mode == ShadingMode::kTextures ? scene.shading.layers.size() : 0;
  resources.textures.resize(layers);
  std::vector<std::exception_ptr> failures(layers);
  tbb::parallel_for(std::size_t(0), layers, [&](std::size_t k) {
    try {
      const std::string path = "shading.layers[" + std::to_string(k) + "].texture";
      resources.textures[k] = build_proto_texture(
          load_layer_texture(scene.shading.layers[k], scene.shading.texture_size, path),
          scene.shading.mip_blend);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  });
  for (const std::exception_ptr& failure : failures) {
    if (failure) {
      std::rethrow_exception(failure);
    }
  }
  resources.sketch = load_height_sketch(scene);
  const std::optional<HeightFieldSettings>& field = scene.terrain.heightfield;
  if (field && field->geomipmap && resources.sketch) {  // GeoMipMapping's tiles, once per scene
    try {
      resources.field_mesh =
          build_field_mesh(*resources.sketch, sketch_extent(*field, *resources.sketch),
                           field->geomipmap->tile_cells, thread_pool_rows());
    } catch (const std::invalid_argument& e) {
      throw SceneError("terrain.heightfield.geomipmap", e.what());
    }
  }
  resources.basis = load_basis_grid(scene, &resources.notes);
  resources.skybox = load_skybox(scene);
  check_planet_depth(scene, resources);
  return resources;
}

bool same_resource_inputs(const Scene& a, const Scene& b) {
  // The settings as relief scene prints them: every field, compared by value.
  const nlohmann::json ja = scene_to_json(a), jb = scene_to_json(b);
  // The skybox's texels: its faces and intensity (sun_disc is a parameter of the frame).
  const auto texels = [](const Scene& s) {
    return s.sky.skybox ? std::optional(std::pair(s.sky.skybox->faces, s.sky.skybox->intensity))
                        : std::nullopt;
  };
  return ja.at("terrain") == jb.at("terrain") && ja.at("shading") == jb.at("shading") &&
         texels(a) == texels(b);
}

}  // namespace relief
