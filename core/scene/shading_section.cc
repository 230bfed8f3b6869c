// The scene file's "shading" section: the material layers (§4.2) and how they are sampled.
#include <algorithm>
#include <charconv>
#include <string>
#include <string_view>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

const std::vector<std::string>& builtin_texture_names() {
  static const std::vector<std::string> names = {"sand", "grass",  "rock", "snow",
                                                 "bed",  "basalt", "dune"};
  return names;
}

// "builtin:NAME" for a texture synthesised at start-up, or a PNG path.
Field<MaterialLayer> texture_field() {
  Field<MaterialLayer> field = input_file_field(
      "texture", &MaterialLayer::texture,
      {"", "the proto-texture",
       "PNG: square, a power of two from 4 to 4096 pixels, 8-bit RGB or RGBA (alpha ignored)"});
  field.info.allowed = "`builtin:" + join(builtin_texture_names(), "`, `builtin:") +
                       "`, or a PNG path (relative to the scene file)";
  for (const std::string& name : builtin_texture_names()) {
    field.info.words.push_back(std::string(kBuiltinPrefix) + name);
  }
  field.read = [](const LayerContext& cx, const json& v, const std::string& p, MaterialLayer& s) {
    const std::string texture = cx.in.string(v, p);
    if (texture.rfind(kBuiltinPrefix, 0) == 0) {
      const std::string name = texture.substr(kBuiltinPrefix.size());
      const auto& names = builtin_texture_names();
      if (std::find(names.begin(), names.end(), name) == names.end()) {
        cx.in.fail(p, p + " = " + brief(v) + " names no built-in texture; allowed: builtin:" +
                          join(names, ", builtin:") + ", or a PNG file");
      }
    }
    s.texture = resolve_scene_path(texture, cx.base_dir);
  };
  return field;
}

const Schema<MaterialLayer>& layer_schema() {
  using S = MaterialLayer;
  static const Schema<S> schema({
      text_field("name", &S::name, {"", "the layer's name", "unique among the layers"}),
      texture_field(),
      number_field("tile_size", &S::tile_size, Range{limits::kMinTileSize, limits::kMaxTileSize},
                   {"world units", "per repeat of the texture"}),
      increasing_pair_field("height", &S::height,
                            Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight},
                            {"world units", "heights where the layer is present"}),
      boolean_field("height_relative_to_water", &S::height_relative_to_water,
                    {"", "heights measured from terrain.water_level (from 0 when it is null)"}),
      increasing_pair_field("slope_deg", &S::slope_deg, Range{0.0, limits::kMaxSlopeDeg},
                            {"degrees", "slope angles where the layer is present (atan |∇h|)"}),
      number_field("height_spread", &S::height_spread, Range{0.0, limits::kMaxShadingLength},
                   {"world units", "half-width of the height transitions"}),
      number_field("slope_spread_deg", &S::slope_spread_deg, Range{0.0, limits::kMaxSlopeSpreadDeg},
                   {"degrees", "half-width of the slope transitions"}),
      number_field("specular", &S::specular, Range{0.0, 1.0}, {"", "Phong specular strength"}),
  });
  return schema;
}

// shading.layers: an array replaces the whole list; an object {"2": {...}} patches layer 2
// (that is what --set shading.layers.2.slope_deg=[30,90] produces).
void read_layers(const LayerContext& cx, const json& value, const std::string& path,
                 std::vector<MaterialLayer>& layers) {
  if (value.is_array()) {
    if (value.empty() || value.size() > limits::kMaxMaterialLayers) {
      cx.in.fail(path, path + " has " + std::to_string(value.size()) + " layers; allowed 1 to " +
                           std::to_string(limits::kMaxMaterialLayers));
    }
    std::vector<MaterialLayer> replaced(value.size());
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string p = path + "[" + std::to_string(k) + "]";
      if (!value[k].is_object() || !value[k].contains("texture")) {
        cx.in.fail(p, p + " must be an object with at least a \"texture\"");
      }
      replaced[k].name = "layer" + std::to_string(k);
      layer_schema().apply(cx, value[k], p, replaced[k]);
    }
    layers = std::move(replaced);
    return;
  }
  if (!value.is_object()) {
    cx.in.fail(path, path + " = " + brief(value) +
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
      cx.in.fail(path, "no layer '" + brief_text(key) + "' in " + path + "; allowed indices 0 to " +
                           std::to_string(layers.size() - 1));
    }
    layer_schema().apply(cx, item, path + "[" + key + "]", layers[index]);
  }
}

Field<ShadingSettings> layers_field() {
  return {{"layers",
           "array of 1 to " + std::to_string(limits::kMaxMaterialLayers) +
               " objects, each with a `texture` (replaces the list), or an object patching "
               "layers by index (`{\"2\": {...}}`)",
           {"", "the material layers (§4.2), each with the fields below"},
           {},
           &layer_schema(),
           true},
          [](const LayerContext& cx, const json& v, const std::string& p, ShadingSettings& s) {
            read_layers(cx, v, p, s.layers);
          },
          [](const ShadingSettings& s) -> std::optional<json> {
            json layers = json::array();
            for (const MaterialLayer& layer : s.layers) {
              layers.push_back(layer_schema().write(layer));
            }
            return layers;
          }};
}

}  // namespace

const Schema<ShadingSettings>& shading_schema() {
  using S = ShadingSettings;
  static const Schema<S> schema({
      choice_field("mode", &S::mode,
                   {{"textures", ShadingMode::kTextures}, {"gradient", ShadingMode::kGradient}},
                   {"",
                    "the terrain's colour: the layers' proto-textures (§4.2), or castledragmire's "
                    "height-to-colour gradient lit per vertex (Gouraud shading)"}),
      section_field("gradient", &S::gradient, gradient_schema(),
                    {"", "the height gradient of mode `gradient`"}),
      layers_field(),
      power_of_two_field("texture_size", &S::texture_size, limits::kMinBuiltinTextureSize,
                         limits::kMaxBuiltinTextureSize,
                         {"texels", "side of the built-in textures"}),
      number_field("mip_blend", &S::mip_blend, Range{0.0, 1.0},
                   {"", "§4.2: each mip level blended this far toward the mean colour"}),
      boolean_field("triplanar", &S::triplanar,
                    {"", "three projections weighted by squared normals (Mekala, Scape)"}),
      choice_field(
          "texture_filter", &S::texture_filter,
          {{"trilinear", TextureFilter::kTrilinear}, {"bilinear", TextureFilter::kBilinear}},
          {"",
           "between mip levels: GL_LINEAR_MIPMAP_LINEAR, or the nearest level "
           "alone (GL_LINEAR_MIPMAP_NEAREST: one fetch instead of two)"}),
      number_field("dither", &S::dither, Range{0.0, limits::kMaxDither},
                   {"spreads", "transition dithering, in units of each layer's spreads"}),
      number_field("dither_scale", &S::dither_scale,
                   Range{limits::kMinInverseScaleLength, limits::kMaxShadingLength},
                   {"world units",
                    "per cell of the dithering noise; it fades out where a pixel "
                    "spans more than half a cell"}),
  });
  return schema;
}

}  // namespace relief
