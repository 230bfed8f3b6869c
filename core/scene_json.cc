#include "core/scene_json.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <utility>

#include "core/limits.h"
#include "core/scene_presets.h"

namespace relief {

using nlohmann::json;

namespace {

// A closed or open interval, printed the way messages quote it: "1 < terrain.r <= 16".
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

// Shortest text that reads back to the same double ("90", "0.85", "1e+30").
std::string format_number(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string describe(const Range& range, const std::string& path) {
  return format_number(range.lo) + (range.lo_open ? " < " : " <= ") + path +
         (range.hi_open ? " < " : " <= ") + format_number(range.hi);
}

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (std::size_t k = 0; k < items.size(); ++k) {
    out += (k ? std::string(separator) : std::string()) + items[k];
  }
  return out;
}

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// Reads one layer field by field. Every failure names the layer's source and the JSON path.
class LayerReader {
 public:
  explicit LayerReader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw SceneError(path, std::string(source_) + ": " + problem);
  }

  // Visits each key of an object, rejecting keys not in `handlers`.
  void object(const json& value, const std::string& path,
              const std::vector<
                  std::pair<std::string, std::function<void(const json&, const std::string&)>>>&
                  handlers) const {
    if (!value.is_object()) {
      fail(path, (path.empty() ? std::string("the scene") : path) + " must be a JSON object, got " +
                     value.dump());
    }
    for (const auto& [key, item] : value.items()) {
      const auto handler = std::find_if(handlers.begin(), handlers.end(),
                                        [&](const auto& h) { return h.first == key; });
      if (handler == handlers.end()) {
        std::vector<std::string> known;
        for (const auto& h : handlers) {
          known.push_back(h.first);
        }
        fail(child_path(path, key), "unknown key '" + child_path(path, key) + "'; allowed keys" +
                                        (path.empty() ? "" : " in " + path) + ": " +
                                        join(known, ", "));
      }
      handler->second(item, child_path(path, key));
    }
  }

  double number(const json& value, const std::string& path, const Range& range) const {
    if (!value.is_number()) {
      fail(path,
           path + " = " + value.dump() + " is not a number; allowed " + describe(range, path));
    }
    const double v = value.get<double>();
    if (!std::isfinite(v)) {
      fail(path, path + " = " + value.dump() + " is not a finite number");
    }
    if (!range.contains(v)) {
      fail(path,
           path + " = " + format_number(v) + " is out of range; allowed " + describe(range, path));
    }
    return v;
  }

  long long integer(const json& value, const std::string& path, long long lo, long long hi) const {
    const Range range{static_cast<double>(lo), static_cast<double>(hi)};
    if (!value.is_number_integer()) {
      fail(path,
           path + " = " + value.dump() + " is not an integer; allowed " + describe(range, path));
    }
    if (value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
      fail(path,
           path + " = " + value.dump() + " is out of range; allowed " + describe(range, path));
    }
    const long long v = value.get<long long>();
    if (v < lo || v > hi) {
      fail(path,
           path + " = " + value.dump() + " is out of range; allowed " + describe(range, path));
    }
    return v;
  }

  std::uint64_t unsigned64(const json& value, const std::string& path) const {
    if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<long long>() < 0)) {
      fail(path, path + " = " + value.dump() + " is not an unsigned integer; allowed 0 <= " + path +
                     " <= 18446744073709551615");
    }
    return value.get<std::uint64_t>();
  }

  bool boolean(const json& value, const std::string& path) const {
    if (!value.is_boolean()) {
      fail(path, path + " = " + value.dump() + " is not a boolean; allowed true or false");
    }
    return value.get<bool>();
  }

  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) {
      fail(path, path + " = " + value.dump() + " is not a string");
    }
    std::string s = value.get<std::string>();
    if (s.empty()) {
      fail(path, path + " is empty; a path is required");
    }
    return s;
  }

  template <class Enum>
  Enum choice(const json& value, const std::string& path,
              const std::vector<std::pair<std::string, Enum>>& names) const {
    std::vector<std::string> allowed;
    for (const auto& [name, e] : names) {
      allowed.push_back(name);
    }
    if (value.is_string()) {
      for (const auto& [name, e] : names) {
        if (name == value.get<std::string>()) {
          return e;
        }
      }
    }
    fail(path, path + " = " + value.dump() + " is not allowed; allowed: " + join(allowed, ", "));
  }

  template <std::size_t N>
  std::array<double, N> vector(const json& value, const std::string& path,
                               const Range& range) const {
    if (!value.is_array() || value.size() != N) {
      fail(path,
           path + " = " + value.dump() + " must be an array of " + std::to_string(N) + " numbers");
    }
    std::array<double, N> out{};
    for (std::size_t k = 0; k < N; ++k) {
      out[k] = number(value[k], path + "[" + std::to_string(k) + "]", range);
    }
    return out;
  }

 private:
  std::string_view source_;
};

using Handlers =
    std::vector<std::pair<std::string, std::function<void(const json&, const std::string&)>>>;

constexpr double kInf = std::numeric_limits<double>::infinity();

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
             camera.yaw_deg = in.number(v, p, Range{-360.0, 360.0});
             angles_given = true;
           }},
          {"pitch_deg",
           [&](const json& v, const std::string& p) {
             camera.pitch_deg = in.number(v, p, Range{-90.0, 90.0});
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
             camera.near = in.number(v, p, Range{0.0, limits::kMaxViewDistance, true});
           }},
          {"far",
           [&](const json& v, const std::string& p) {
             camera.far = in.number(v, p, Range{0.0, limits::kMaxViewDistance, true});
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
            });
}

void apply_terrain(const LayerReader& in, const json& value, const std::string& path,
                   TerrainSettings& terrain) {
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
               in.fail(p, p + " = " + v.dump() + " is not a power of two; allowed 4, 8, 16, ..., " +
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
             terrain.r = in.number(v, p, Range{1.0, limits::kMaxLacunarity, true});
           }},
          {"H",
           [&](const json& v, const std::string& p) {
             terrain.H = in.number(v, p, Range{0.0, limits::kMaxHurst, true});
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
                 in.number(v, p, Range{0.0, limits::kMaxHorizontalScale, true});
           }},
          {"base_height",
           [&](const json& v, const std::string& p) {
             terrain.base_height =
                 in.number(v, p, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight});
           }},
          {"amplitude",
           [&](const json& v, const std::string& p) {
             terrain.amplitude = in.number(v, p, Range{0.0, limits::kMaxAmplitude, true});
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
                 in.fail(p, p + " = " + v.dump() + " names no built-in texture; allowed: builtin:" +
                                join(names, ", builtin:") + ", or a PNG file");
               }
             } else if (!base_dir.empty() && std::filesystem::path(texture).is_relative()) {
               texture = (base_dir / texture).lexically_normal().string();
             }
             layer.texture = texture;
           }},
          {"tile_size",
           [&](const json& v, const std::string& p) {
             layer.tile_size = in.number(v, p, Range{0.0, 1e6, true});
           }},
          {"height",
           [&](const json& v, const std::string& p) {
             layer.height =
                 in.vector<2>(v, p, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight});
             if (!(layer.height[0] < layer.height[1])) {
               in.fail(p, p + " = " + v.dump() + " is empty; allowed [low, high] with low < high");
             }
           }},
          {"height_relative_to_water",
           [&](const json& v, const std::string& p) {
             layer.height_relative_to_water = in.boolean(v, p);
           }},
          {"slope_deg",
           [&](const json& v, const std::string& p) {
             layer.slope_deg = in.vector<2>(v, p, Range{0.0, 90.0});
             if (!(layer.slope_deg[0] < layer.slope_deg[1])) {
               in.fail(p, p + " = " + v.dump() + " is empty; allowed [low, high] with low < high");
             }
           }},
          {"height_spread",
           [&](const json& v, const std::string& p) {
             layer.height_spread = in.number(v, p, Range{0.0, 1e6});
           }},
          {"slope_spread_deg",
           [&](const json& v, const std::string& p) {
             layer.slope_spread_deg = in.number(v, p, Range{0.0, 45.0});
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
    in.fail(path, path + " = " + value.dump() +
                      " must be an array of layers, or an object patching layers by index");
  }
  for (const auto& [key, item] : value.items()) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), index);
    if (ec != std::errc() || end != key.data() + key.size() || index >= layers.size()) {
      in.fail(path, "no layer '" + key + "' in " + path + "; allowed indices 0 to " +
                        std::to_string(layers.size() - 1));
    }
    apply_material_layer(in, item, path + "[" + key + "]", layers[index], base_dir);
  }
}

void apply_shading(const LayerReader& in, const json& value, const std::string& path,
                   ShadingSettings& shading, const std::filesystem::path& base_dir) {
  in.object(value, path,
            Handlers{
                {"layers",
                 [&](const json& v, const std::string& p) {
                   apply_material_layers(in, v, p, shading.layers, base_dir);
                 }},
                {"texture_size",
                 [&](const json& v, const std::string& p) {
                   const long long size = in.integer(v, p, 16, 2048);
                   if (!std::has_single_bit(static_cast<unsigned long long>(size))) {
                     in.fail(p, p + " = " + v.dump() +
                                    " is not a power of two; allowed 16, 32, ..., 2048");
                   }
                   shading.texture_size = static_cast<int>(size);
                 }},
                {"mip_blend",
                 [&](const json& v, const std::string& p) {
                   shading.mip_blend = in.number(v, p, Range{0.0, 1.0});
                 }},
                {"triplanar", [&](const json& v,
                                  const std::string& p) { shading.triplanar = in.boolean(v, p); }},
                {"dither",
                 [&](const json& v, const std::string& p) {
                   shading.dither = in.number(v, p, Range{0.0, 4.0});
                 }},
                {"dither_scale",
                 [&](const json& v, const std::string& p) {
                   shading.dither_scale = in.number(v, p, Range{0.0, 1e6, true});
                 }},
            });
}

void apply_lighting(const LayerReader& in, const json& value, const std::string& path,
                    LightingSettings& l) {
  const Range color{0.0, 1000.0};
  in.object(
      value, path,
      Handlers{
          {"sun_azimuth_deg",
           [&](const json& v, const std::string& p) {
             l.sun_azimuth_deg = in.number(v, p, Range{-360.0, 360.0});
           }},
          {"sun_elevation_deg",
           [&](const json& v, const std::string& p) {
             l.sun_elevation_deg = in.number(v, p, Range{-90.0, 90.0});
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
             l.shininess = in.number(v, p, Range{1.0, 10000.0});
           }},
          {"exposure",
           [&](const json& v, const std::string& p) {
             l.exposure = in.number(v, p, Range{0.0, 1000.0, true});
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
             w.extinction = in.vector<3>(v, p, Range{0.0, 100.0});
           }},
          {"full_depth",
           [&](const json& v, const std::string& p) {
             w.full_depth = in.number(v, p, Range{0.0, 1e6, true});
           }},
          {"wave_length",
           [&](const json& v, const std::string& p) {
             w.wave_length = in.number(v, p, Range{0.0, 1e6, true});
           }},
          {"wave_strength",
           [&](const json& v, const std::string& p) {
             w.wave_strength = in.number(v, p, Range{0.0, 10.0});
           }},
          {"wave_speed",
           [&](const json& v, const std::string& p) {
             w.wave_speed = in.number(v, p, Range{0.0, 1e6});
           }},
      });
}

void apply_sky(const LayerReader& in, const json& value, const std::string& path, SkySettings& s) {
  const Range color{0.0, 1000.0};
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
                   s.sun_disc_deg = in.number(v, p, Range{0.0, 10.0});
                 }},
                {"fog_density",
                 [&](const json& v, const std::string& p) {
                   s.fog_density = in.number(v, p, Range{0.0, 1.0});
                 }},
            });
}

void apply_output(const LayerReader& in, const json& value, const std::string& path,
                  OutputSettings& output) {
  in.object(
      value, path,
      Handlers{
          {"image", [&](const json& v, const std::string& p) { output.image = in.string(v, p); }},
          {"stages_dir",
           [&](const json& v, const std::string& p) { output.stages_dir = in.string(v, p); }},
          {"float_image",
           [&](const json& v, const std::string& p) {
             if (v.is_null()) {
               output.float_image.reset();
             } else {
               output.float_image = in.string(v, p);
             }
           }},
      });
}

json vec_json(const Vec2d& v) {
  return json::array({v[0], v[1]});
}
json vec_json(const Vec3d& v) {
  return json::array({v[0], v[1], v[2]});
}

bool looks_non_finite(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
    text.erase(0, 1);
  }
  return text == "nan" || text == "inf" || text == "infinity";
}

json read_scene_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw SceneError("", "scene file " + file.string() + ": cannot be opened for reading");
  }
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::exception& e) {
    throw SceneError("", "scene file " + file.string() + ": not valid JSON: " + e.what() +
                             " (numbers must be finite; NaN and Infinity are not JSON)");
  }
}

}  // namespace

void apply_scene_layer(Scene& scene, const json& layer, std::string_view source,
                       const std::filesystem::path& base_dir) {
  const LayerReader in(source);
  in.object(
      layer, "",
      Handlers{
          {"camera",
           [&](const json& v, const std::string& p) { apply_camera(in, v, p, scene.camera); }},
          {"viewport",
           [&](const json& v, const std::string& p) { apply_viewport(in, v, p, scene.viewport); }},
          {"grid", [&](const json& v, const std::string& p) { apply_grid(in, v, p, scene.grid); }},
          {"terrain",
           [&](const json& v, const std::string& p) { apply_terrain(in, v, p, scene.terrain); }},
          {"shading",
           [&](const json& v, const std::string& p) {
             apply_shading(in, v, p, scene.shading, base_dir);
           }},
          {"lighting",
           [&](const json& v, const std::string& p) { apply_lighting(in, v, p, scene.lighting); }},
          {"water",
           [&](const json& v, const std::string& p) { apply_water(in, v, p, scene.water); }},
          {"sky", [&](const json& v, const std::string& p) { apply_sky(in, v, p, scene.sky); }},
          {"time",
           [&](const json& v, const std::string& p) {
             scene.time = in.number(v, p, Range{-1e9, 1e9});
           }},
          {"output",
           [&](const json& v, const std::string& p) { apply_output(in, v, p, scene.output); }},
      });
}

void validate_scene(const Scene& scene) {
  auto fail = [](const std::string& path, const std::string& message) {
    throw SceneError(path, "scene: " + message);
  };
  const TerrainSettings& t = scene.terrain;
  if (t.last_octave < t.first_octave) {
    fail("terrain.last_octave",
         "terrain.last_octave = " + std::to_string(t.last_octave) +
             " is below terrain.first_octave = " + std::to_string(t.first_octave) +
             "; allowed terrain.first_octave <= terrain.last_octave");
  }
  if (t.last_octave - t.first_octave + 1 > limits::kMaxOctaves) {
    fail("terrain.last_octave", "terrain.last_octave - terrain.first_octave + 1 = " +
                                    std::to_string(t.last_octave - t.first_octave + 1) +
                                    " octaves; allowed at most " +
                                    std::to_string(limits::kMaxOctaves));
  }
  // Octave frequencies r^k must stay representable in float lattice coordinates.
  const double max_log2_frequency = t.last_octave * std::log2(t.r);
  if (max_log2_frequency > 40.0) {
    fail("terrain.last_octave", "terrain.last_octave = " + std::to_string(t.last_octave) +
                                    " with terrain.r = " + format_number(t.r) +
                                    " gives octave frequencies up to 2^" +
                                    format_number(std::round(max_log2_frequency)) +
                                    "; allowed terrain.last_octave * log2(terrain.r) <= 40");
  }
  const GridSettings& g = scene.grid;
  const int min_side = 2 * g.margin + 2;
  if (g.width < min_side || g.height < min_side) {
    fail(g.width < min_side ? "grid.width" : "grid.height",
         "grid " + std::to_string(g.width) + "x" + std::to_string(g.height) +
             " is too small for grid.margin = " + std::to_string(g.margin) +
             "; allowed grid.width and grid.height >= 2 * grid.margin + 2 = " +
             std::to_string(min_side));
  }
  const CameraSettings& c = scene.camera;
  if (!(c.near < c.far)) {
    fail("camera.far", "camera.far = " + format_number(c.far) + " is not beyond camera.near = " +
                           format_number(c.near) + "; allowed camera.near < camera.far");
  }
  const double aspect = static_cast<double>(scene.viewport.width) / scene.viewport.height;
  const double horizontal_fov_deg =
      2.0 * std::atan(std::tan(c.fov_y_deg * M_PI / 360.0) * aspect) * 180.0 / M_PI;
  if (horizontal_fov_deg > limits::kMaxHorizontalFovDeg) {
    fail("camera.fov_y_deg",
         "camera.fov_y_deg = " + format_number(c.fov_y_deg) + " with viewport " +
             std::to_string(scene.viewport.width) + "x" + std::to_string(scene.viewport.height) +
             " gives a horizontal field of view of " + format_number(horizontal_fov_deg) +
             " degrees; allowed at most " + format_number(limits::kMaxHorizontalFovDeg));
  }
  const std::vector<MaterialLayer>& layers = scene.shading.layers;
  for (std::size_t a = 0; a < layers.size(); ++a) {
    for (std::size_t b = a + 1; b < layers.size(); ++b) {
      if (layers[a].name == layers[b].name) {
        fail("shading.layers", "shading.layers[" + std::to_string(a) + "] and [" +
                                   std::to_string(b) + "] are both named '" + layers[a].name +
                                   "'; layer names must be unique");
      }
    }
  }
  const WarpSettings& w = scene.terrain.warp;
  if (w.r0[0] == 0.0 && w.r0[1] == 0.0) {
    fail("terrain.warp.r0",
         "terrain.warp.r0 = [0, 0] has no direction; allowed any non-zero vector");
  }
}

json scene_to_json(const Scene& scene) {
  const CameraSettings& c = scene.camera;
  const TerrainSettings& t = scene.terrain;
  json out;
  out["camera"] = {
      {"position", vec_json(c.position)}, {"yaw_deg", c.yaw_deg}, {"pitch_deg", c.pitch_deg},
      {"fov_y_deg", c.fov_y_deg},         {"near", c.near},       {"far", c.far}};
  out["viewport"] = {{"width", scene.viewport.width}, {"height", scene.viewport.height}};
  out["grid"] = {
      {"width", scene.grid.width}, {"height", scene.grid.height}, {"margin", scene.grid.margin}};
  out["terrain"] = {
      {"seed", t.seed},
      {"lattice_size", t.lattice_size},
      {"interpolant", std::string(interpolant_name(t.interpolant))},
      {"r", t.r},
      {"H", t.H},
      {"first_octave", t.first_octave},
      {"last_octave", t.last_octave},
      {"lod",
       {{"criterion", t.lod.criterion == LodCriterion::kAmplitude ? "amplitude" : "nyquist"},
        {"bias", t.lod.bias}}},
      {"warp",
       {{"enabled", t.warp.enabled},
        {"c1", vec_json(t.warp.c1)},
        {"c2", vec_json(t.warp.c2)},
        {"c3", vec_json(t.warp.c3)},
        {"r0", vec_json(t.warp.r0)},
        {"t0", vec_json(t.warp.t0)}}},
      {"horizontal_scale", t.horizontal_scale},
      {"base_height", t.base_height},
      {"amplitude", t.amplitude},
      {"water_level", t.water_level ? json(*t.water_level) : json(nullptr)}};
  json layers = json::array();
  for (const MaterialLayer& l : scene.shading.layers) {
    layers.push_back({{"name", l.name},
                      {"texture", l.texture},
                      {"tile_size", l.tile_size},
                      {"height", vec_json(l.height)},
                      {"height_relative_to_water", l.height_relative_to_water},
                      {"slope_deg", vec_json(l.slope_deg)},
                      {"height_spread", l.height_spread},
                      {"slope_spread_deg", l.slope_spread_deg},
                      {"specular", l.specular}});
  }
  const ShadingSettings& sh = scene.shading;
  out["shading"] = {{"layers", layers},          {"texture_size", sh.texture_size},
                    {"mip_blend", sh.mip_blend}, {"triplanar", sh.triplanar},
                    {"dither", sh.dither},       {"dither_scale", sh.dither_scale}};
  const LightingSettings& li = scene.lighting;
  out["lighting"] = {{"sun_azimuth_deg", li.sun_azimuth_deg},
                     {"sun_elevation_deg", li.sun_elevation_deg},
                     {"sun_color", vec_json(li.sun_color)},
                     {"sun_intensity", li.sun_intensity},
                     {"sky_color", vec_json(li.sky_color)},
                     {"ground_color", vec_json(li.ground_color)},
                     {"sky_intensity", li.sky_intensity},
                     {"ambient", li.ambient},
                     {"shininess", li.shininess},
                     {"exposure", li.exposure}};
  const WaterSettings& wa = scene.water;
  out["water"] = {{"shallow_color", vec_json(wa.shallow_color)},
                  {"deep_color", vec_json(wa.deep_color)},
                  {"extinction", vec_json(wa.extinction)},
                  {"full_depth", wa.full_depth},
                  {"wave_length", wa.wave_length},
                  {"wave_strength", wa.wave_strength},
                  {"wave_speed", wa.wave_speed}};
  out["sky"] = {{"zenith_color", vec_json(scene.sky.zenith_color)},
                {"horizon_color", vec_json(scene.sky.horizon_color)},
                {"sun_disc_deg", scene.sky.sun_disc_deg},
                {"fog_density", scene.sky.fog_density}};
  out["time"] = scene.time;
  out["output"] = {
      {"image", scene.output.image},
      {"stages_dir", scene.output.stages_dir},
      {"float_image", scene.output.float_image ? json(*scene.output.float_image) : json(nullptr)}};
  return out;
}

json parse_override(std::string_view assignment) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    throw SceneError("", "--set " + std::string(assignment) +
                             ": expected KEY=VALUE, for example --set terrain.H=0.85");
  }
  const std::string key(assignment.substr(0, equals));
  const std::string text(assignment.substr(equals + 1));
  json value;
  try {
    value = json::parse(text);
  } catch (const json::out_of_range&) {
    throw SceneError(key, "--set " + std::string(assignment) + ": " + key + " = " + text +
                              " is not a finite number");
  } catch (const json::parse_error&) {
    if (looks_non_finite(text)) {
      throw SceneError(key, "--set " + std::string(assignment) + ": " + key + " = " + text +
                                " is not a finite number");
    }
    value = text;  // a bare word such as quintic
  }
  // Build {"a": {"b": value}} from "a.b"; each segment is checked by apply_scene_layer.
  json layer = value;
  std::size_t end = key.size();
  while (true) {
    const std::size_t dot = key.rfind('.', end - 1);
    const std::size_t begin = dot == std::string::npos ? 0 : dot + 1;
    const std::string segment = key.substr(begin, end - begin);
    if (segment.empty()) {
      throw SceneError(
          key, "--set " + std::string(assignment) + ": key '" + key + "' has an empty segment");
    }
    layer = json{{segment, layer}};
    if (dot == std::string::npos) {
      break;
    }
    end = dot;
  }
  return layer;
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names{"default"};
  for (const ScenePreset& preset : scene_presets()) {
    names.emplace_back(preset.name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool is_preset(std::string_view name) {
  const auto names = preset_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene resolve_scene(std::string_view scene_arg, const std::vector<std::string>& overrides) {
  Scene scene;
  const std::string name = scene_arg.empty() ? std::string("default") : std::string(scene_arg);
  const std::filesystem::path file(name);
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) {
    apply_scene_layer(scene, read_scene_file(file), "scene file " + name, file.parent_path());
  } else if (name == "default") {
    // The defaults are the member initialisers of scene.h.
  } else if (is_preset(name)) {
    for (const ScenePreset& preset : scene_presets()) {
      if (preset.name == name) {
        apply_scene_layer(scene, json::parse(preset.json), "preset " + name);
      }
    }
  } else {
    throw SceneError("", "scene '" + name + "' is neither a readable file nor a preset; presets: " +
                             join(preset_names(), ", "));
  }
  for (const std::string& assignment : overrides) {
    apply_scene_layer(scene, parse_override(assignment), "--set " + assignment);
  }
  validate_scene(scene);
  return scene;
}

}  // namespace relief
