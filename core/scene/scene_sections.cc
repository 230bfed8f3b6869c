#include "core/scene/scene_sections.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <optional>

#include "core/limits.h"

namespace relief {

namespace {

void apply_warp(const LayerReader& in, const json& value, const std::string& path,
                WarpSettings& warp) {
  const Range component{-limits::kMaxWarpComponent, limits::kMaxWarpComponent};
  auto vec = [&](Vec2d& target) {
    return [&in, &target, component](const json& v, const std::string& p) {
      target = in.vector<2>(v, p, component);
    };
  };
  in.object(value, path,
            Handlers{
                {"enabled",
                 [&](const json& v, const std::string& p) { warp.enabled = in.boolean(v, p); }},
                {"c1", vec(warp.c1)},
                {"c2", vec(warp.c2)},
                {"c3", vec(warp.c3)},
                {"r0", vec(warp.r0)},
                {"t0", vec(warp.t0)},
            });
}

void apply_lod(const LayerReader& in, const json& value, const std::string& path,
               LodSettings& lod) {
  in.object(value, path,
            Handlers{
                {"criterion",
                 [&](const json& v, const std::string& p) {
                   lod.criterion = in.choice<LodCriterion>(v, p,
                                                           {{"amplitude", LodCriterion::kAmplitude},
                                                            {"nyquist", LodCriterion::kNyquist}});
                 }},
                {"bias",
                 [&](const json& v, const std::string& p) {
                   lod.bias = in.number(v, p, Range{-limits::kMaxLodBias, limits::kMaxLodBias});
                 }},
                {"fractional",
                 [&](const json& v, const std::string& p) { lod.fractional = in.boolean(v, p); }},
            });
}

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

void apply_camera(const LayerReader& in, const json& value, const std::string& path,
                  CameraSettings& camera) {
  const Range coordinate{-limits::kMaxCameraCoordinate, limits::kMaxCameraCoordinate};
  bool angles_given = false;
  std::optional<Vec3d> look_at;
  in.object(
      value, path,
      Handlers{
          {"position",
           [&](const json& v, const std::string& p) {
             camera.position = in.vector<3>(v, p, coordinate);
           }},
          {"yaw_deg",
           [&](const json& v, const std::string& p) {
             camera.yaw_deg = in.number(v, p, Range{-limits::kMaxTurnDeg, limits::kMaxTurnDeg});
             angles_given = true;
           }},
          {"pitch_deg",
           [&](const json& v, const std::string& p) {
             camera.pitch_deg =
                 in.number(v, p, Range{-limits::kMaxElevationDeg, limits::kMaxElevationDeg});
             angles_given = true;
           }},
          {"look_at",
           [&](const json& v, const std::string& p) { look_at = in.vector<3>(v, p, coordinate); }},
          {"fov_y_deg",
           [&](const json& v, const std::string& p) {
             camera.fov_y_deg = in.number(v, p, Range{limits::kMinFovDeg, limits::kMaxFovDeg});
           }},
          {"near",
           [&](const json& v, const std::string& p) {
             camera.near =
                 in.number(v, p, Range{limits::kMinNearDistance, limits::kMaxViewDistance});
           }},
          {"far",
           [&](const json& v, const std::string& p) {
             camera.far =
                 in.number(v, p, Range{limits::kMinNearDistance, limits::kMaxViewDistance, true});
           }},
      });
  if (look_at) {
    const std::string p = child_path(path, "look_at");
    if (angles_given) {
      in.fail(p, p + " and " + child_path(path, "yaw_deg") + "/" + child_path(path, "pitch_deg") +
                     " both set the view direction; give one or the other");
    }
    // Converted to yaw/pitch at load time so that later layers can still adjust the angles.
    const double dx = (*look_at)[0] - camera.position[0];
    const double dy = (*look_at)[1] - camera.position[1];
    const double dz = (*look_at)[2] - camera.position[2];
    const double horizontal = std::hypot(dx, dz);
    if (horizontal == 0.0 && dy == 0.0) {
      in.fail(p, p + " = the camera position; the target must differ from camera.position");
    }
    camera.yaw_deg = horizontal > 0.0 ? std::atan2(dx, -dz) * (180.0 / M_PI) : camera.yaw_deg;
    camera.pitch_deg = std::atan2(dy, horizontal) * (180.0 / M_PI);
  }
}

void apply_viewport(const LayerReader& in, const json& value, const std::string& path,
                    ViewportSettings& viewport) {
  in.object(value, path,
            Handlers{
                {"width",
                 [&](const json& v, const std::string& p) {
                   viewport.width = static_cast<int>(in.integer(v, p, 1, limits::kMaxViewportSide));
                 }},
                {"height",
                 [&](const json& v, const std::string& p) {
                   viewport.height =
                       static_cast<int>(in.integer(v, p, 1, limits::kMaxViewportSide));
                 }},
            });
}

void apply_grid(const LayerReader& in, const json& value, const std::string& path,
                GridSettings& grid) {
  in.object(
      value, path,
      Handlers{
          {"width",
           [&](const json& v, const std::string& p) {
             grid.width =
                 static_cast<int>(in.integer(v, p, limits::kMinGridSide, limits::kMaxGridSide));
           }},
          {"height",
           [&](const json& v, const std::string& p) {
             grid.height =
                 static_cast<int>(in.integer(v, p, limits::kMinGridSide, limits::kMaxGridSide));
           }},
          {"margin",
           [&](const json& v, const std::string& p) {
             grid.margin = static_cast<int>(in.integer(v, p, 0, limits::kMaxGridMargin));
           }},
      });
}

void apply_terrain(const LayerReader& in, const json& value, const std::string& path,
                   TerrainSettings& terrain, const std::filesystem::path& base_dir) {
  in.object(
      value, path,
      Handlers{
          {"seed",
           [&](const json& v, const std::string& p) { terrain.seed = in.unsigned64(v, p); }},
          {"lattice_size",
           [&](const json& v, const std::string& p) {
             const long long size =
                 in.integer(v, p, limits::kMinLatticeSize, limits::kMaxLatticeSize);
             if (!std::has_single_bit(static_cast<unsigned long long>(size))) {
               in.fail(p, p + " = " + brief(v) + " is not a power of two; allowed 4, 8, 16, ..., " +
                              std::to_string(limits::kMaxLatticeSize));
             }
             terrain.lattice_size = static_cast<int>(size);
           }},
          {"interpolant",
           [&](const json& v, const std::string& p) {
             terrain.interpolant = in.choice<Interpolant>(v, p,
                                                          {{"linear", Interpolant::kLinear},
                                                           {"cubic", Interpolant::kCubic},
                                                           {"quintic", Interpolant::kQuintic}});
           }},
          {"r",
           [&](const json& v, const std::string& p) {
             terrain.r = in.number(v, p, Range{limits::kMinLacunarity, limits::kMaxLacunarity});
           }},
          {"H",
           [&](const json& v, const std::string& p) {
             terrain.H = in.number(v, p, Range{limits::kMinHurst, limits::kMaxHurst});
           }},
          {"first_octave",
           [&](const json& v, const std::string& p) {
             terrain.first_octave = static_cast<int>(in.integer(v, p, 0, limits::kMaxFirstOctave));
           }},
          {"last_octave",
           [&](const json& v, const std::string& p) {
             terrain.last_octave = static_cast<int>(
                 in.integer(v, p, 0, limits::kMaxFirstOctave + limits::kMaxOctaves - 1));
           }},
          {"lod", [&](const json& v, const std::string& p) { apply_lod(in, v, p, terrain.lod); }},
          {"warp",
           [&](const json& v, const std::string& p) { apply_warp(in, v, p, terrain.warp); }},
          {"horizontal_scale",
           [&](const json& v, const std::string& p) {
             terrain.horizontal_scale =
                 in.number(v, p, Range{limits::kMinHorizontalScale, limits::kMaxHorizontalScale});
           }},
          {"base_height",
           [&](const json& v, const std::string& p) {
             terrain.base_height =
                 in.number(v, p, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight});
           }},
          {"amplitude",
           [&](const json& v, const std::string& p) {
             terrain.amplitude =
                 in.number(v, p, Range{limits::kMinAmplitude, limits::kMaxAmplitude});
           }},
          {"water_level",
           [&](const json& v, const std::string& p) {
             if (v.is_null()) {
               terrain.water_level.reset();
             } else {
               terrain.water_level =
                   in.number(v, p, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight});
             }
           }},
          {"sketch",
           [&](const json& v, const std::string& p) {
             apply_sketch(in, v, p, terrain.sketch, base_dir);
           }},
      });
}

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

void apply_lighting(const LayerReader& in, const json& value, const std::string& path,
                    LightingSettings& l) {
  const Range color{0.0, limits::kMaxRadiance};
  in.object(
      value, path,
      Handlers{
          {"sun_azimuth_deg",
           [&](const json& v, const std::string& p) {
             l.sun_azimuth_deg = in.number(v, p, Range{-limits::kMaxTurnDeg, limits::kMaxTurnDeg});
           }},
          {"sun_elevation_deg",
           [&](const json& v, const std::string& p) {
             l.sun_elevation_deg =
                 in.number(v, p, Range{-limits::kMaxElevationDeg, limits::kMaxElevationDeg});
           }},
          {"sun_color",
           [&](const json& v, const std::string& p) { l.sun_color = in.vector<3>(v, p, color); }},
          {"sun_intensity",
           [&](const json& v, const std::string& p) { l.sun_intensity = in.number(v, p, color); }},
          {"sky_color",
           [&](const json& v, const std::string& p) { l.sky_color = in.vector<3>(v, p, color); }},
          {"ground_color",
           [&](const json& v, const std::string& p) {
             l.ground_color = in.vector<3>(v, p, color);
           }},
          {"sky_intensity",
           [&](const json& v, const std::string& p) { l.sky_intensity = in.number(v, p, color); }},
          {"ambient",
           [&](const json& v, const std::string& p) { l.ambient = in.number(v, p, color); }},
          {"shininess",
           [&](const json& v, const std::string& p) {
             l.shininess = in.number(v, p, Range{limits::kMinShininess, limits::kMaxShininess});
           }},
          {"exposure",
           [&](const json& v, const std::string& p) {
             l.exposure = in.number(v, p, Range{limits::kMinExposure, limits::kMaxExposure});
           }},
      });
}

void apply_water(const LayerReader& in, const json& value, const std::string& path,
                 WaterSettings& w) {
  const Range unit{0.0, 1.0};
  in.object(
      value, path,
      Handlers{
          {"shallow_color",
           [&](const json& v, const std::string& p) {
             w.shallow_color = in.vector<3>(v, p, unit);
           }},
          {"deep_color",
           [&](const json& v, const std::string& p) { w.deep_color = in.vector<3>(v, p, unit); }},
          {"extinction",
           [&](const json& v, const std::string& p) {
             w.extinction = in.vector<3>(v, p, Range{0.0, limits::kMaxExtinction});
           }},
          {"full_depth",
           [&](const json& v, const std::string& p) {
             w.full_depth =
                 in.number(v, p, Range{limits::kMinInverseScaleLength, limits::kMaxShadingLength});
           }},
          {"wave_length",
           [&](const json& v, const std::string& p) {
             w.wave_length =
                 in.number(v, p, Range{limits::kMinInverseScaleLength, limits::kMaxShadingLength});
           }},
          {"wave_strength",
           [&](const json& v, const std::string& p) {
             w.wave_strength = in.number(v, p, Range{0.0, limits::kMaxWaveStrength});
           }},
          {"wave_speed",
           [&](const json& v, const std::string& p) {
             w.wave_speed = in.number(v, p, Range{0.0, limits::kMaxWaveSpeed});
           }},
      });
}

void apply_sky(const LayerReader& in, const json& value, const std::string& path, SkySettings& s) {
  const Range color{0.0, limits::kMaxRadiance};
  in.object(value, path,
            Handlers{
                {"zenith_color",
                 [&](const json& v, const std::string& p) {
                   s.zenith_color = in.vector<3>(v, p, color);
                 }},
                {"horizon_color",
                 [&](const json& v, const std::string& p) {
                   s.horizon_color = in.vector<3>(v, p, color);
                 }},
                {"sun_disc_deg",
                 [&](const json& v, const std::string& p) {
                   s.sun_disc_deg =
                       in.number(v, p, Range{limits::kMinSunDiscDeg, limits::kMaxSunDiscDeg});
                 }},
                {"fog_density",
                 [&](const json& v, const std::string& p) {
                   s.fog_density = in.number(v, p, Range{0.0, limits::kMaxFogDensity});
                 }},
            });
}

void apply_output(const LayerReader& in, const json& value, const std::string& path,
                  OutputSettings& output) {
  in.object(value, path,
            Handlers{
                {"image",
                 [&](const json& v, const std::string& p) {
                   output.image = in.file_name(v, p, {".png"}, "the image is written as PNG");
                 }},
                {"stages_dir",
                 [&](const json& v, const std::string& p) { output.stages_dir = in.string(v, p); }},
                {"float_image",
                 [&](const json& v, const std::string& p) {
                   if (v.is_null()) {
                     output.float_image.reset();
                   } else {
                     output.float_image = in.file_name(v, p, {".pfm", ".exr"},
                                                       "linear radiance is written as PFM or EXR");
                   }
                 }},
            });
}

}  // namespace relief
