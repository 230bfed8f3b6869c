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
          {"basis", [&](const json& v,
                        const std::string& p) { apply_basis(in, v, p, terrain.basis, base_dir); }},
          {"planet",
           [&](const json& v, const std::string& p) { apply_planet(in, v, p, terrain.planet); }},
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
