// The scene file's "lighting", "water", "sky" and "output" sections
// (docs/scene-reference.md).
#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

constexpr Range kRadiance{0.0, limits::kMaxRadiance};
constexpr Range kShadingLength{limits::kMinInverseScaleLength, limits::kMaxShadingLength};

// sky.skybox.faces: six paths, +x, -x, +y, -y, +z, -z, each made absolute like a texture's.
Field<SkyboxSettings> faces_field() {
  return {{"faces",
           "an array of 6 file paths (relative to the scene file)",
           {"", "the cube's faces +x, −x, +y, −y, +z, −z (GL's order and orientation)",
            "PNG: square, 8-bit, a power of two 4…2048, all six of one size"}},
          [](const LayerContext& cx, const json& v, const std::string& p, SkyboxSettings& s) {
            if (!v.is_array() || v.size() != s.faces.size()) {
              cx.in.fail(p, p + " = " + brief(v) +
                                " is not an array of 6 paths; allowed: [+x, -x, +y, -y, +z, -z]");
            }
            for (std::size_t k = 0; k < s.faces.size(); ++k) {
              const std::string item = p + "[" + std::to_string(k) + "]";
              const std::string name = cx.in.string(v[k], item);
              if (name.empty() || name.starts_with("builtin:")) {
                cx.in.fail(item, item + " = " + brief(v[k]) +
                                     " names no file; allowed: a PNG file's path (there are no "
                                     "built-in faces)");
              }
              s.faces[k] = resolve_scene_path(name, cx.base_dir);
            }
          },
          [](const SkyboxSettings& s) -> std::optional<json> { return json(s.faces); }};
}

const Schema<SkyboxSettings>& skybox_schema() {
  using S = SkyboxSettings;
  static const Schema<S> schema({
      faces_field(),
      number_field("intensity", &S::intensity, kRadiance,
                   {"", "linear radiance of a white texel (faces are sRGB-decoded)"}),
      boolean_field("sun_disc", &S::sun_disc,
                    {"", "the sun's disc and halo drawn over the faces (off: the faces' own sun)"}),
  });
  return schema;
}

const Schema<AtmosphereSettings>& atmosphere_schema() {
  using S = AtmosphereSettings;
  const Range scattering{0.0, limits::kMaxScattering};
  static const Schema<S> schema({
      number_field("scale_height", &S::scale_height,
                   Range{limits::kMinScaleHeight, limits::kMaxScaleHeight},
                   {"world units", "the air thins by e over this height (0 is height 0)"}),
      vector_field("rayleigh", &S::rayleigh, scattering,
                   {"per world unit", "RGB scattering of the air at height 0 (blue sky)"}),
      number_field("mie", &S::mie, scattering,
                   {"per world unit", "grey scattering of haze at height 0 (extinction / 0.9)"}),
      vector_field("absorption", &S::absorption, scattering,
                   {"per world unit",
                    "RGB absorption at height 0 without scattering (ozone: the twilight's blue)"}),
      number_field("mie_g", &S::mie_g, Range{0.0, limits::kMaxMieG},
                   {"", "the haze's forward scattering (0: even, 0.95: a tight glow)"}),
      number_field("intensity", &S::intensity, kRadiance,
                   {"", "the sun in the sky's light, times lighting's sun"}),
  });
  return schema;
}

const Schema<CloudSettings>& clouds_schema() {
  using S = CloudSettings;
  const Range heights{-limits::kMaxBaseHeight, limits::kMaxBaseHeight};
  static const Schema<S> schema({
      number_field("altitude", &S::altitude, heights,
                   {"world units", "height of the cloud layer's bottom"}),
      number_field("thickness", &S::thickness,
                   Range{limits::kMinCloudThickness, limits::kMaxShadingLength},
                   {"world units", "the layer's depth: cloud fills its heights"}),
      number_field("coverage", &S::coverage, Range{0.0, 1.0},
                   {"", "share of the layer's area holding cloud (0: none, 1: overcast)"}),
      number_field("density", &S::density, Range{0.0, limits::kMaxExtinction},
                   {"per world unit", "extinction where the cloud is full"}),
      number_field("scale", &S::scale, Range{limits::kMinCloudScale, limits::kMaxShadingLength},
                   {"world units", "per lattice cell of the largest octave"}),
      integer_field("octaves", &S::octaves, 1, limits::kMaxCloudOctaves,
                    {"", "each of twice the frequency and half the amplitude of the last"}),
      number_field("warp", &S::warp, Range{0.0, limits::kMaxCloudWarp},
                   {"lattice cells", "domain warp of the largest octave's cells (0: none)"}),
      vector_field("color", &S::color, Range{0.0, 1.0},
                   {"", "albedo: the share of the sun's and the sky's light it returns"}),
  });
  return schema;
}

}  // namespace

const Schema<LightingSettings>& lighting_schema() {
  using S = LightingSettings;
  static const Schema<S> schema({
      number_field("sun_azimuth_deg", &S::sun_azimuth_deg,
                   Range{-limits::kMaxTurnDeg, limits::kMaxTurnDeg},
                   {"degrees", "0: the sun stands toward −z, 90: toward +x (like camera yaw)"}),
      number_field("sun_elevation_deg", &S::sun_elevation_deg,
                   Range{-limits::kMaxElevationDeg, limits::kMaxElevationDeg},
                   {"degrees", "the sun's height above the horizon"}),
      vector_field("sun_color", &S::sun_color, kRadiance, {"", "sun colour (linear RGB)"}),
      number_field("sun_intensity", &S::sun_intensity, kRadiance, {"", "sun radiance scale"}),
      vector_field("sky_color", &S::sky_color, kRadiance,
                   {"", "hemispherical light from above (Scape)"}),
      vector_field("ground_color", &S::ground_color, kRadiance,
                   {"", "hemispherical light from below"}),
      number_field("sky_intensity", &S::sky_intensity, kRadiance,
                   {"", "hemispherical light's scale"}),
      number_field("ambient", &S::ambient, kRadiance, {"", "constant light"}),
      number_field("shininess", &S::shininess, Range{limits::kMinShininess, limits::kMaxShininess},
                   {"", "Phong exponent of the layers' specular term"}),
      number_field("exposure", &S::exposure, Range{limits::kMinExposure, limits::kMaxExposure},
                   {"", "linear radiance scale before sRGB encoding"}),
      boolean_field("shadows", &S::shadows,
                    {"", "cast shadows: the terrain's horizon toward the sun (not on planets)"}),
      power_of_two_field("shadow_resolution", &S::shadow_resolution, limits::kMinShadowResolution,
                         limits::kMaxShadowResolution,
                         {"samples", "per side of each level of the shadows' horizon cache"}),
      boolean_field("sky_occlusion", &S::sky_occlusion,
                    {"",
                     "sky light: the hemispherical light's sky share scaled by the sky the "
                     "terrain leaves open above each point (not on planets)"}),
  });
  return schema;
}

const Schema<WaterSettings>& water_schema() {
  using S = WaterSettings;
  const Range unit{0.0, 1.0};
  static const Schema<S> schema({
      vector_field("shallow_color", &S::shallow_color, unit,
                   {"", "water body colour in shallow water (§4.3)"}),
      vector_field("deep_color", &S::deep_color, unit,
                   {"", "and in deep water (\"the green-ish hue\")"}),
      vector_field("extinction", &S::extinction, Range{0.0, limits::kMaxExtinction},
                   {"per world unit", "RGB attenuation of the transmitted light"}),
      number_field("full_depth", &S::full_depth, kShadingLength,
                   {"world units", "depth of the deep look and full reflectivity"}),
      number_field("wave_length", &S::wave_length, kShadingLength,
                   {"world units", "the largest wave of the normal map"}),
      number_field("wave_strength", &S::wave_strength, Range{0.0, limits::kMaxWaveStrength},
                   {"", "slope of the wave normal map in deep water"}),
      number_field("wave_speed", &S::wave_speed, Range{0.0, limits::kMaxWaveSpeed},
                   {"world units per second", "the waves' drift"}),
      boolean_field("reflect_terrain", &S::reflect_terrain,
                    {"",
                     "the terrain reflected in the water, traced from its surface over the "
                     "shadows' horizon cache (not on planets)"}),
  });
  return schema;
}

const Schema<SkySettings>& sky_schema() {
  using S = SkySettings;
  static const Schema<S> schema({
      vector_field("zenith_color", &S::zenith_color, kRadiance, {"", "the sky gradient's top"}),
      vector_field("horizon_color", &S::horizon_color, kRadiance,
                   {"", "its bottom, also the fog colour"}),
      number_field("sun_disc_deg", &S::sun_disc_deg,
                   Range{limits::kMinSunDiscDeg, limits::kMaxSunDiscDeg},
                   {"degrees", "angular radius of the sun disc"}),
      number_field("fog_density", &S::fog_density, Range{0.0, limits::kMaxFogDensity},
                   {"per world unit", "fog = 1 − exp(−density · distance)"}),
      optional_section_field("skybox", &S::skybox, skybox_schema(), "faces", "\"faces\"",
                             {"",
                              "six images in place of the gradient above the horizon and in "
                              "the water's reflection (docs/stages.md, \"Skybox\"); `null`: the "
                              "gradient"}),
      optional_section_field("atmosphere", &S::atmosphere, atmosphere_schema(), "", "",
                             {"",
                              "sky and aerial perspective from the sun's light scattered once "
                              "(docs/stages.md, \"Atmosphere\"), in place of the gradient and "
                              "the fog; `null`: the gradient and the fog"}),
      optional_section_field("clouds", &S::clouds, clouds_schema(), "", "",
                             {"",
                              "a fractal cloud layer over the sky and the terrain, shadowing the "
                              "ground (docs/stages.md, \"Clouds\"; not on planets); `null`: a "
                              "clear sky"}),
  });
  return schema;
}

const Schema<OutputSettings>& output_schema() {
  using S = OutputSettings;
  static const Schema<S> schema({
      output_file_field("image", &S::image, {".png"}, "the image is written as PNG",
                        {"", "the image `render` writes"}),
      text_field("stages_dir", &S::stages_dir, {"", "the directory `stages` writes"}),
      nullable_output_file_field("float_image", &S::float_image, {".pfm", ".exr"},
                                 "linear radiance is written as PFM or EXR",
                                 {"", "linear radiance `render` writes; `null`: none"}),
  });
  return schema;
}

}  // namespace relief
