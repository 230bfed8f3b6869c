// The scene file's "shading" section: the material layers (§4.2) and how they are sampled.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

#include "core/limits.h"
#include "core/scene/scene_sections.h"

namespace relief {

namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

const std::vector<std::string>& builtin_texture_names() {
  static const std::vector<std::string> names = {"sand", "grass",  "rock", "snow",
                                                 "bed",  "basalt", "dune"};
  return names;
}

// A layer given as an object: every key optional, applied onto `layer`.

void apply_material_layer(const LayerReader& in, const json& value, const std::string& path,
                          MaterialLayer& layer, const std::filesystem::path& base_dir) {
  in.object(
      value, path,
      Handlers{
          {"name", [&](const json& v, const std::string& p) { layer.name = in.string(v, p); }},
          {"texture",
           [&](const json& v, const std::string& p) {
             std::string texture = in.string(v, p);
             if (texture.rfind(kBuiltinPrefix, 0) == 0) {
               const std::string name = texture.substr(kBuiltinPrefix.size());
               const auto& names = builtin_texture_names();
               if (std::find(names.begin(), names.end(), name) == names.end()) {
                 in.fail(p, p + " = " + brief(v) + " names no built-in texture; allowed: builtin:" +
                                join(names, ", builtin:") + ", or a PNG file");
               }
             } else if (std::filesystem::path(texture).is_relative()) {
               // Relative to the scene file's directory (the current one for --set), made
               // absolute so that the printed scene loads back from anywhere.
               std::error_code ec;
               const std::filesystem::path absolute =
                   std::filesystem::absolute(base_dir / texture, ec);
               texture = ec ? (base_dir / texture).lexically_normal().string()
                            : absolute.lexically_normal().string();
             }
             layer.texture = texture;
           }},
          {"tile_size",
           [&](const json& v, const std::string& p) {
             layer.tile_size = in.number(v, p, Range{limits::kMinTileSize, limits::kMaxTileSize});
           }},
          {"height",
           [&](const json& v, const std::string& p) {
             layer.height =
                 in.vector<2>(v, p, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight});
             if (!(layer.height[0] < layer.height[1])) {
               in.fail(p, p + " = " + brief(v) + " is empty; allowed [low, high] with low < high");
             }
           }},
          {"height_relative_to_water",
           [&](const json& v, const std::string& p) {
             layer.height_relative_to_water = in.boolean(v, p);
           }},
          {"slope_deg",
           [&](const json& v, const std::string& p) {
             layer.slope_deg = in.vector<2>(v, p, Range{0.0, limits::kMaxSlopeDeg});
             if (!(layer.slope_deg[0] < layer.slope_deg[1])) {
               in.fail(p, p + " = " + brief(v) + " is empty; allowed [low, high] with low < high");
             }
           }},
          {"height_spread",
           [&](const json& v, const std::string& p) {
             layer.height_spread = in.number(v, p, Range{0.0, limits::kMaxShadingLength});
           }},
          {"slope_spread_deg",
           [&](const json& v, const std::string& p) {
             layer.slope_spread_deg = in.number(v, p, Range{0.0, limits::kMaxSlopeSpreadDeg});
           }},
          {"specular",
           [&](const json& v, const std::string& p) {
             layer.specular = in.number(v, p, Range{0.0, 1.0});
           }},
      });
}

// shading.layers: an array replaces the whole list; an object {"2": {...}} patches layer 2
// (that is what --set shading.layers.2.slope_deg=[30,90] produces).

void apply_material_layers(const LayerReader& in, const json& value, const std::string& path,
                           std::vector<MaterialLayer>& layers,
                           const std::filesystem::path& base_dir) {
  if (value.is_array()) {
    if (value.empty() || value.size() > limits::kMaxMaterialLayers) {
      in.fail(path, path + " has " + std::to_string(value.size()) + " layers; allowed 1 to " +
                        std::to_string(limits::kMaxMaterialLayers));
    }
    std::vector<MaterialLayer> replaced(value.size());
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string p = path + "[" + std::to_string(k) + "]";
      if (!value[k].is_object() || !value[k].contains("texture")) {
        in.fail(p, p + " must be an object with at least a \"texture\"");
      }
      replaced[k].name = "layer" + std::to_string(k);
      apply_material_layer(in, value[k], p, replaced[k], base_dir);
    }
    layers = std::move(replaced);
    return;
  }
  if (!value.is_object()) {
    in.fail(path, path + " = " + brief(value) +
                      " must be an array of layers, or an object patching layers by index");
  }
  for (const auto& [key, item] : value.items()) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), index);
    // Indices are written as decimals without leading zeros, so that "1" and "01" cannot both
    // patch layer 1 in one object (one of them would be dropped).
    const bool canonical = key.size() == 1 || key[0] != '0';
    if (ec != std::errc() || end != key.data() + key.size() || index >= layers.size() ||
        !canonical) {
      in.fail(path, "no layer '" + brief_text(key) + "' in " + path + "; allowed indices 0 to " +
                        std::to_string(layers.size() - 1));
    }
    apply_material_layer(in, item, path + "[" + key + "]", layers[index], base_dir);
  }
}

}  // namespace

void apply_shading(const LayerReader& in, const json& value, const std::string& path,
                   ShadingSettings& shading, const std::filesystem::path& base_dir) {
  in.object(
      value, path,
      Handlers{
          {"layers",
           [&](const json& v, const std::string& p) {
             apply_material_layers(in, v, p, shading.layers, base_dir);
           }},
          {"texture_size",
           [&](const json& v, const std::string& p) {
             const long long size =
                 in.integer(v, p, limits::kMinBuiltinTextureSize, limits::kMaxBuiltinTextureSize);
             if (!std::has_single_bit(static_cast<unsigned long long>(size))) {
               in.fail(p, p + " = " + brief(v) + " is not a power of two; allowed " +
                              std::to_string(limits::kMinBuiltinTextureSize) + ", " +
                              std::to_string(2 * limits::kMinBuiltinTextureSize) + ", ..., " +
                              std::to_string(limits::kMaxBuiltinTextureSize));
             }
             shading.texture_size = static_cast<int>(size);
           }},
          {"mip_blend",
           [&](const json& v, const std::string& p) {
             shading.mip_blend = in.number(v, p, Range{0.0, 1.0});
           }},
          {"triplanar",
           [&](const json& v, const std::string& p) { shading.triplanar = in.boolean(v, p); }},
          {"texture_filter",
           [&](const json& v, const std::string& p) {
             shading.texture_filter =
                 in.choice<TextureFilter>(v, p,
                                          {{"trilinear", TextureFilter::kTrilinear},
                                           {"bilinear", TextureFilter::kBilinear}});
           }},
          {"dither",
           [&](const json& v, const std::string& p) {
             shading.dither = in.number(v, p, Range{0.0, limits::kMaxDither});
           }},
          {"dither_scale",
           [&](const json& v, const std::string& p) {
             shading.dither_scale =
                 in.number(v, p, Range{limits::kMinInverseScaleLength, limits::kMaxShadingLength});
           }},
      });
}

}  // namespace relief
