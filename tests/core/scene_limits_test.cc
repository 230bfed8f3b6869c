// The float-meaningful range of every numeric scene field (core/limits.h, derived in
// docs/scene-limits.md): the value just outside each bound is refused with a message that names
// the field, the value and the range, and every derived bound satisfies the inequality it is
// derived from. Frames rendered at the bounds, and the cases of the issue that asked for them:
// tests/core/scene_limits_frame_test.cc.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "raster/resolve.h"
#include "tests/core/scene_limits_support.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;
using test::scene_limits::above;
using test::scene_limits::below;
using test::scene_limits::cat;
using test::scene_limits::error_of;
using test::scene_limits::kSmallFrame;

// A field read by LayerReader::number (one entry in `value`) or LayerReader::vector (several).
struct RealField {
  std::string key;            // as --set writes it
  std::string path;           // as messages name it (shading.layers[3].tile_size)
  std::vector<double> value;  // an accepted value; one entry for a scalar
  double lo, hi;
  bool lo_open = false;
  bool hi_open = false;
};

// Every field read as a real number, with the range docs/scene-limits.md gives it.
std::vector<RealField> real_fields() {
  const double kColor = 1000;
  return {
      {"camera.position", "camera.position", {0, 700, 0}, -1e12, 1e12},
      {"camera.yaw_deg", "camera.yaw_deg", {30}, -360, 360},
      {"camera.pitch_deg", "camera.pitch_deg", {-8}, -90, 90},
      {"camera.look_at", "camera.look_at", {100, 0, -100}, -1e12, 1e12},
      {"camera.fov_y_deg", "camera.fov_y_deg", {60}, 1, 170},
      {"camera.near", "camera.near", {0.5}, 1e-17, 1e9},
      {"camera.far", "camera.far", {60000}, 1e-17, 1e9, true},
      {"terrain.r", "terrain.r", {2}, 1.001, 16},
      {"terrain.H", "terrain.H", {0.85}, 0.00025, 1},
      {"terrain.lod.bias", "terrain.lod.bias", {0}, -8, 8},
      {"terrain.warp.c1", "terrain.warp.c1", {0.35, 0.16}, -100, 100},
      {"terrain.warp.c2", "terrain.warp.c2", {-0.07, 0.13}, -100, 100},
      {"terrain.warp.c3", "terrain.warp.c3", {0.11, 0.17}, -100, 100},
      {"terrain.warp.r0", "terrain.warp.r0", {1, 0}, -100, 100},
      {"terrain.warp.t0", "terrain.warp.t0", {0, 0}, -100, 100},
      {"terrain.horizontal_scale", "terrain.horizontal_scale", {3000}, 1e-15, 1e9},
      {"terrain.base_height", "terrain.base_height", {100}, -1e7, 1e7},
      {"terrain.amplitude", "terrain.amplitude", {360}, 1e-25, 1e7},
      {"terrain.water_level", "terrain.water_level", {0}, -1e7, 1e7},
      {"shading.layers.3.tile_size", "shading.layers[3].tile_size", {60}, 1e-4, 1e6},
      {"shading.layers.2.height", "shading.layers[2].height", {30, 560}, -1e7, 1e7},
      {"shading.layers.2.slope_deg", "shading.layers[2].slope_deg", {0, 38}, 0, 90},
      {"shading.layers.2.height_spread", "shading.layers[2].height_spread", {25}, 0, 1e6},
      {"shading.layers.2.slope_spread_deg", "shading.layers[2].slope_spread_deg", {5}, 0, 45},
      {"shading.layers.4.specular", "shading.layers[4].specular", {0.35}, 0, 1},
      {"shading.mip_blend", "shading.mip_blend", {0.3}, 0, 1},
      {"shading.dither", "shading.dither", {0.6}, 0, 4},
      {"shading.dither_scale", "shading.dither_scale", {9}, 1e-26, 1e6},
      {"lighting.sun_azimuth_deg", "lighting.sun_azimuth_deg", {230}, -360, 360},
      {"lighting.sun_elevation_deg", "lighting.sun_elevation_deg", {24}, -90, 90},
      {"lighting.sun_color", "lighting.sun_color", {1, 0.93, 0.82}, 0, kColor},
      {"lighting.sun_intensity", "lighting.sun_intensity", {1.8}, 0, kColor},
      {"lighting.sky_color", "lighting.sky_color", {0.42, 0.58, 0.85}, 0, kColor},
      {"lighting.ground_color", "lighting.ground_color", {0.22, 0.2, 0.16}, 0, kColor},
      {"lighting.sky_intensity", "lighting.sky_intensity", {0.25}, 0, kColor},
      {"lighting.ambient", "lighting.ambient", {0.03}, 0, kColor},
      {"lighting.shininess", "lighting.shininess", {48}, 1, 10000},
      {"lighting.exposure", "lighting.exposure", {0.75}, 1e-11, 1000},
      {"water.shallow_color", "water.shallow_color", {0.08, 0.3, 0.28}, 0, 1},
      {"water.deep_color", "water.deep_color", {0.015, 0.09, 0.085}, 0, 1},
      {"water.extinction", "water.extinction", {0.42, 0.11, 0.075}, 0, 100},
      {"water.full_depth", "water.full_depth", {14}, 1e-26, 1e6},
      {"water.wave_length", "water.wave_length", {7}, 1e-26, 1e6},
      {"water.wave_strength", "water.wave_strength", {0.2}, 0, 10},
      {"water.wave_speed", "water.wave_speed", {1.2}, 0, 1e6},
      {"sky.zenith_color", "sky.zenith_color", {0.17, 0.33, 0.7}, 0, kColor},
      {"sky.horizon_color", "sky.horizon_color", {0.66, 0.75, 0.86}, 0, kColor},
      {"sky.sun_disc_deg", "sky.sun_disc_deg", {0.6}, 0.11, 10},
      {"sky.fog_density", "sky.fog_density", {2.2e-5}, 0, 1},
      {"sky.atmosphere.scale_height", "sky.atmosphere.scale_height", {8000}, 10, 1e6},
      {"sky.atmosphere.rayleigh", "sky.atmosphere.rayleigh", {5.8e-6, 13.5e-6, 33.1e-6}, 0, 1e-2},
      {"sky.atmosphere.mie", "sky.atmosphere.mie", {3.2e-6}, 0, 1e-2},
      {"sky.atmosphere.absorption",
       "sky.atmosphere.absorption",
       {0.65e-6, 1.881e-6, 0.085e-6},
       0,
       1e-2},
      {"sky.atmosphere.mie_g", "sky.atmosphere.mie_g", {0.76}, 0, 0.95},
      {"sky.atmosphere.intensity", "sky.atmosphere.intensity", {20}, 0, kColor},
      {"time", "time", {0}, -1e9, 1e9},
  };
}

// The --set text of `field` with component `k` replaced by `v`.
std::string assignment(const RealField& field, std::size_t k, double v) {
  std::vector<double> value = field.value;
  value[k] = v;
  std::string text = field.key + "=";
  if (value.size() == 1) {
    return text.append(format_number(v));
  }
  text.append("[");
  for (std::size_t c = 0; c < value.size(); ++c) {
    text.append(c ? ", " : "").append(format_number(value[c]));
  }
  return text.append("]");
}

TEST_CASE("everyRealFieldRefusesTheValueJustOutsideEachBoundNamingFieldValueAndRange", "[limits]") {
  for (const RealField& field : real_fields()) {
    for (std::size_t k = 0; k < field.value.size(); ++k) {
      const std::string path =
          field.value.size() == 1 ? field.path : cat({field.path, "[", std::to_string(k), "]"});
      const std::string range = cat({format_number(field.lo), field.lo_open ? " < " : " <= ", path,
                                     field.hi_open ? " < " : " <= ", format_number(field.hi)});
      for (const double outside : {field.lo_open ? field.lo : below(field.lo),
                                   field.hi_open ? field.hi : above(field.hi)}) {
        const std::string set = assignment(field, k, outside);
        INFO("--set " << set);
        const std::string message = error_of({set});
        CHECK_THAT(message, Contains(cat({path, " = ", format_number(outside),
                                          " is out of range; allowed ", range})));
      }
      // The bounds themselves are accepted (or refused only by a rule across fields).
      for (const double inside : {field.lo, field.hi}) {
        if ((inside == field.lo && field.lo_open) || (inside == field.hi && field.hi_open)) {
          continue;
        }
        const std::string set = assignment(field, k, inside);
        INFO("--set " << set);
        CHECK_THAT(error_of({set}), !Contains("is out of range"));
      }
    }
  }
}

// Fields read as integers: the value just outside each bound, and the message.
struct IntegerCase {
  std::string set;
  std::string message;
};

TEST_CASE("everyIntegerFieldRefusesTheValueJustOutsideEachBoundNamingFieldValueAndRange",
          "[limits]") {
  const std::vector<IntegerCase> cases = {
      {"viewport.width=0",
       "viewport.width = 0 is out of range; allowed 1 <= viewport.width <= 16384"},
      {"viewport.width=16385",
       "viewport.width = 16385 is out of range; allowed 1 <= viewport.width <= 16384"},
      {"viewport.height=0",
       "viewport.height = 0 is out of range; allowed 1 <= viewport.height <= 16384"},
      {"viewport.height=16385",
       "viewport.height = 16385 is out of range; allowed 1 <= viewport.height <= 16384"},
      {"grid.width=1", "grid.width = 1 is out of range; allowed 2 <= grid.width <= 8192"},
      {"grid.width=8193", "grid.width = 8193 is out of range; allowed 2 <= grid.width <= 8192"},
      {"grid.height=1", "grid.height = 1 is out of range; allowed 2 <= grid.height <= 8192"},
      {"grid.height=8193", "grid.height = 8193 is out of range; allowed 2 <= grid.height <= 8192"},
      {"grid.margin=-1", "grid.margin = -1 is out of range; allowed 0 <= grid.margin <= 64"},
      {"grid.margin=65", "grid.margin = 65 is out of range; allowed 0 <= grid.margin <= 64"},
      {"terrain.seed=-1", "terrain.seed = -1 is not an unsigned integer"},
      {"terrain.seed=18446744073709551616", "allowed 0 <= terrain.seed <= 18446744073709551615"},
      {"terrain.lattice_size=2",
       "terrain.lattice_size = 2 is out of range; allowed 4 <= terrain.lattice_size <= 4096"},
      {"terrain.lattice_size=8192",
       "terrain.lattice_size = 8192 is out of range; allowed 4 <= terrain.lattice_size <= 4096"},
      {"terrain.first_octave=-1",
       "terrain.first_octave = -1 is out of range; allowed 0 <= terrain.first_octave <= 32"},
      {"terrain.first_octave=33",
       "terrain.first_octave = 33 is out of range; allowed 0 <= terrain.first_octave <= 32"},
      {"terrain.last_octave=-1",
       "terrain.last_octave = -1 is out of range; allowed 0 <= terrain.last_octave <= 55"},
      {"terrain.last_octave=56",
       "terrain.last_octave = 56 is out of range; allowed 0 <= terrain.last_octave <= 55"},
      {"shading.texture_size=8",
       "shading.texture_size = 8 is out of range; allowed 16 <= shading.texture_size <= 2048"},
      {"shading.texture_size=4096",
       "shading.texture_size = 4096 is out of range; allowed 16 <= shading.texture_size <= 2048"},
  };
  for (const IntegerCase& c : cases) {
    INFO("--set " << c.set);
    CHECK_THAT(error_of({c.set}), Contains(c.message));
  }
}

TEST_CASE("rulesAcrossFieldsRefuseTheValueJustBeyondThemNamingTheFieldsAndTheRange", "[limits]") {
  // camera.near below camera.far.
  CHECK_THAT(error_of({"camera.near=60000"}),
             Contains("camera.far = 60000 is not beyond camera.near = 60000; allowed camera.near "
                      "< camera.far"));
  CHECK(error_of({cat({"camera.near=", format_number(below(60000))})}).empty());
  // The amplitude LOD rule: H log2 r >= 2^-10 (here r = 2: H >= 2^-10).
  CHECK_THAT(error_of({cat({"terrain.H=", format_number(below(0x1p-10))})}),
             Contains("allowed terrain.H * log2(terrain.r) >= 0.0009765625, here terrain.H >= "
                      "0.0009765625"));
  CHECK(error_of({"terrain.H=0.0009765625"}).empty());
  CHECK(error_of({"terrain.H=0.00025", "terrain.lod.criterion=nyquist"}).empty());
  // The coarsest octave's lattice coordinate at the farthest footprint stays below 2^24: the
  // default view of the small frame (aspect 4:3) allows horizontal_scale >= F / (2^24 - P),
  // F = 2 far sqrt(1 + tan^2 x + tan^2 y) the farthest footprint, P = 256.
  const double tan_y = std::tan(60.0 * M_PI / 360.0), tan_x = tan_y * (64.0 / 48.0);
  const double farthest = 2 * 60000 * std::sqrt(1 + tan_x * tan_x + tan_y * tan_y);
  const double min_scale = farthest / (16777216.0 - 256.0);
  std::vector<std::string> set = kSmallFrame;
  set.push_back(cat({"terrain.horizontal_scale=", format_number(below(min_scale))}));
  CHECK_THAT(error_of(set),
             Contains(cat({"allowed terrain.horizontal_scale >= ", format_number(min_scale)})));
  set.back() = cat({"terrain.horizontal_scale=", format_number(min_scale)});
  CHECK(error_of(set).empty());
  // The dithering noise needs no such rule: stage 8 samples it only where its cells are larger
  // than the pixel's footprint (shade.cc), so the tiniest scale at the farthest view is fine.
  set.back() = "shading.dither_scale=1e-26";
  CHECK(error_of(set).empty());
  CHECK(error_of({"camera.far=1e9"}).empty());
  // Octave counts, grid versus margin and the horizontal field of view.
  CHECK_THAT(error_of({"terrain.last_octave=24"}), Contains("allowed at most 24"));
  CHECK_THAT(error_of({"terrain.r=16", "terrain.last_octave=11"}),
             Contains("allowed terrain.last_octave * log2(terrain.r) <= 40"));
  CHECK_THAT(error_of({"grid.width=5"}), Contains("allowed grid.width and grid.height >= 2 * "
                                                  "grid.margin + 2 = 6"));
  CHECK_THAT(error_of({"viewport.height=1"}), Contains("allowed 1 to 175"));
  // A tall thin viewport narrows the horizontal field below a degree: neighbouring grid rays
  // would round to the same footprint (seen: 91% of neighbours identical at 1 x 16384).
  CHECK_THAT(error_of({"viewport.width=1", "viewport.height=16384", "camera.fov_y_deg=1"}),
             Contains("gives a horizontal field of view of"));
  CHECK_THAT(error_of({"viewport.width=8", "viewport.height=16384"}), Contains("allowed 1 to 175"));
}

// --- The derivations -----------------------------------------------------------------------

TEST_CASE("everyDerivedBoundSatisfiesTheInequalityItIsDerivedFrom", "[limits]") {
  namespace L = limits;
  const double flt_max = std::numeric_limits<float>::max();
  const double flt_min = std::numeric_limits<float>::min();
  CHECK(L::kFloatMax == flt_max);
  CHECK(L::kFloatMinNormal == flt_min);
  // The largest camera-relative distance: footprints and heights (limits.h).
  const double tan_x = std::tan(L::kMaxHorizontalFovDeg * M_PI / 360.0);
  const double tan_y = std::tan(L::kMaxFovDeg * M_PI / 360.0);
  const double corner = L::kMaxViewDistance * std::sqrt(1 + tan_x * tan_x + tan_y * tan_y);
  const double slab = 2 * (L::kMaxBaseHeight + L::kMaxAmplitude * L::kMaxOctaves * 12.0);
  CHECK(std::hypot(L::kMaxFootprintFactor * corner, corner + slab) <=
        L::kMaxCameraRelativeDistance);
  // camera.near: the squared footprint radius of the narrowest frustum, and reverse-Z depth.
  const double radius = 2 * std::tan(L::kMinFovDeg * M_PI / 360.0) * L::kMinNearDistance;
  CHECK(radius * radius >= flt_min);
  CHECK(L::kMinNearDistance / L::kMaxCameraRelativeDistance >= flt_min);
  CHECK(0.1 * radius * 0.1 * radius < flt_min);  // a decade lower would not do
  // The LOD gain: Nyquist at the smallest r, amplitude at the smallest H with the largest r.
  CHECK(0.5 / std::log2(L::kMinLacunarity) <= L::kMaxLodGain);
  CHECK(0.5 / (L::kMinHurst * std::log2(L::kMaxLacunarity)) <= L::kMaxLodGain);
  // Lattice and texture coordinates and their products stay finite.
  CHECK(std::exp2(40) * L::kMaxCameraRelativeDistance / L::kMinHorizontalScale <= flt_max);
  CHECK(L::kMinAmplitude * std::exp2(-40) >= flt_min);
  const double texels = L::kMaxTextureSize * L::kMaxCameraRelativeDistance / L::kMinTileSize;
  CHECK(texels * texels <= flt_max / 2);
  CHECK(2 * 5.1 * L::kMaxCameraRelativeDistance / L::kMinInverseScaleLength <= flt_max);
  // lighting.exposure: the brightest radiance still reaches the first sRGB code.
  const double brightest = L::kMaxRadiance + 20.06 * L::kMaxRadiance * L::kMaxRadiance;
  CHECK(L::kMinExposure * brightest >= 0.5 / 255 / 12.92);
  // sky.sun_disc_deg: the disc's edge spans 16 float spacings below 1.
  const double theta = L::kMinSunDiscDeg * M_PI / 180;
  CHECK(float(std::cos(theta)) - float(std::cos(1.25 * theta)) >= 16 * 0x1p-24);
}

}  // namespace
}  // namespace relief
