#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "core/atmosphere.h"
#include "core/cloud_plan.h"
#include "core/clouds.h"
#include "core/det_math.h"
#include "core/limits.h"
#include "core/proto_texture.h"
#include "core/shading_plan.h"
#include "gpu/glsl_rounding.h"
#include "gpu/glsl_sources.h"

namespace relief::gpu {

namespace {

// Constants private to core's .cc files, as they are written there (a change there must be
// made here too; tests/gl_shading_test.cc would show it as an image difference).
constexpr double kMinProjectionWeight = 0.01;   // shade.cc: triplanar projections skipped below
constexpr double kMinLayerWeight = 1e-3;        // shade.cc: layers skipped below
constexpr double kMinGrazingSine = 0.05;        // shade.cc, surface_footprint: |view.y| floor
constexpr double kOpenWaterDepth = 1e6;         // shade.cc, background_radiance: no ground
constexpr double kMinWeightSum = 1e-6;          // layer_weights.cc: renormalisation domain
constexpr float kMinRhoSq = 1e-30f;             // proto_texture.cc, texture_lod: log domain
constexpr double kHaloWeight = 0.06;            // sky.cc, sky_radiance
constexpr double kFogSunWeight = 0.05;          // sky.cc, fog_color
constexpr double kFresnelF0 = 0.02;             // water.cc
constexpr double kRelativeIndex = 1.0 / 1.333;  // water.cc: air to water
constexpr double kMinTransmittedCosine = 0.1;   // water.cc: path length domain
constexpr double kReflectivityBase = 0.3;       // water.cc: reflectivity 0.3 + 0.7 f
constexpr double kReflectivityDepth = 0.7;
constexpr double kLocalFrameMinCos = -0.999;  // planet_shading.h, to_local_frame

// The float `value` as a GLSL literal: 9 significant digits identify a float, and the
// decimal lies so close to it that even a parser rounding through double returns it.
std::string literal(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.8e", double(value));
  return text;
}

// The double `value` as a GLSL literal: 17 significant digits identify a double (Mesa parses
// them with strtod, correctly rounded).
std::string literal(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.16eLF", value);
  return text;
}

void constant_double(std::string& out, const std::string& name, double value) {
  out += "const double " + name + " = " + literal(value) + ";\n";
}

// A series' coefficients as RELIEF_<name>_COEFF[RELIEF_<name>_TERMS], the names the float
// series have in the terrain stages' prelude (det_trig.glsl.in reads both).
void double_series(std::string& out, const std::string& name, std::span<const double> values) {
  out += "const int " + name + "_TERMS = " + std::to_string(values.size()) + ";\n";
  out += "const double " + name + "_COEFF[" + std::to_string(values.size()) + "] = double[](";
  for (std::size_t k = 0; k < values.size(); ++k) {
    out += (k > 0 ? ", " : "") + literal(values[k]);
  }
  out += ");\n";
}

void constant(std::string& out, const char* name, float value) {
  out += "const float ";
  out += name;
  out += " = " + literal(value) + ";\n";
}

template <int kCount>
void constant_array(std::string& out, const char* name, const double (&values)[kCount], int count) {
  out += "const float " + std::string(name) + "[" + std::to_string(count) + "] = float[](";
  for (int k = 0; k < count; ++k) {
    out += (k > 0 ? ", " : "") + literal(static_cast<float>(values[k]));
  }
  out += ");\n";
}

std::vector<GlslSource> with_prelude(std::vector<GlslSource> sources) {
  sources.insert(sources.begin(), GlslSource{"prelude", glsl_prelude()});
  return sources;
}

std::vector<GlslSource> shading_sources() {
  return {{"common.glsl", glsl::kCommon},
          {"log2_det.glsl", glsl::kLog2Det},
          {"shade_params.glsl", glsl::kShadeParams},
          {"wrap_period.glsl", glsl::kWrapPeriod},
          {"shading_lattice.glsl", glsl::kLattice},
          {"proto_texture.glsl", glsl::kProtoTexture},
          {"sky.glsl", glsl::kSky},
          {"clouds.glsl", glsl::kClouds},
          {"water.glsl", glsl::kWater},
          {"planet_shading.glsl", glsl::kPlanetShading},
          {"gradient_shading.glsl", glsl::kGradientShading},
          {"terrain_shading.glsl", glsl::kTerrainShading}};
}

}  // namespace

std::string glsl_prelude() {
  using Bits = det_math_detail::FloatBits<float>;
  std::string out = "#version 450 core\n";
  out += "const int kMaxLayers = " + std::to_string(limits::kMaxMaterialLayers) + ";\n";
  // The skybox's texture unit: after the layers' (gl_shading.h, kSkyboxUnit).
  out += "#define RELIEF_SKYBOX_UNIT " + std::to_string(limits::kMaxMaterialLayers) + "\n";
  out += "const int kWaveOctaves = " + std::to_string(kWaveOctaves) + ";\n";
  out += "const int kMaxGradientStops = " + std::to_string(limits::kMaxGradientStops) + ";\n";
  out += "const int kMaxCloudOctaves = " + std::to_string(limits::kMaxCloudOctaves) + ";\n";
  // det_math.h, exp2_det<float>.
  const int exp2_terms = det_math_detail::Exp2Terms<float>::kTerms;
  out += "const int kExp2Terms = " + std::to_string(exp2_terms) + ";\n";
  constant_array(out, "kExp2Coeff", det_math_detail::kExp2Coeffs, exp2_terms);
  constant(out, "kExp2Limit", float(Bits::kExponentBias - 2));
  // log2_det.glsl's constants, under the names the compute stages' prelude gives them.
  constant(out, "RELIEF_SQRT2", float(1.4142135623730951));
  constant(out, "RELIEF_FLT_MIN", Bits::kMinNormal);
  constant(out, "RELIEF_SUBNORMAL_SCALE", Bits::kSubnormalScale);
  out += "const int RELIEF_SUBNORMAL_SHIFT = " + std::to_string(Bits::kSubnormalShift) + ";\n";
  static_assert(Bits::kTerms == 5, "log2_det.glsl spells out five series terms");
  for (int k = 0; k < Bits::kTerms; ++k) {
    constant(out, ("RELIEF_LOG2_COEFF_" + std::to_string(k)).c_str(),
             float(det_math_detail::kAtanhLog2Coeffs[k]));
  }
  // The guards and weights of stage 8.
  constant(out, "kMagnificationLod", kMagnificationLod);
  constant(out, "kMinRhoSq", kMinRhoSq);
  constant(out, "kMinProjectionWeight", float(kMinProjectionWeight));
  constant(out, "kMinLayerWeight", float(kMinLayerWeight));
  constant(out, "kMinGrazingSine", float(kMinGrazingSine));
  constant(out, "kOpenWaterDepth", float(kOpenWaterDepth));
  constant(out, "kMinWeightSum", float(kMinWeightSum));
  constant(out, "kHaloWeight", float(kHaloWeight));
  constant(out, "kFogSunWeight", float(kFogSunWeight));
  constant(out, "kFresnelF0", float(kFresnelF0));
  constant(out, "kFresnelRest", float(1 - kFresnelF0));
  constant(out, "kRelativeIndex", float(kRelativeIndex));
  constant(out, "kMinTransmittedCosine", float(kMinTransmittedCosine));
  constant(out, "kReflectivityBase", float(kReflectivityBase));
  constant(out, "kReflectivityDepth", float(kReflectivityDepth));
  constant(out, "kLocalFrameMinCos", float(kLocalFrameMinCos));
  constant(out, "kMaxOpticalDepth", float(kMaxOpticalDepth));
  constant(out, "kCloudMinSlope", float(kCloudMinSlope));  // clouds.h
  constant(out, "kCloudSpanFootprint", float(kCloudSpanFootprint));
  constant(out, "kCloudMinSunSine", float(kCloudMinSunSine));  // cloud_plan.h
  constant(out, "kMaxCameraRelativeDistance", float(limits::kMaxCameraRelativeDistance));
  constant(out, "kGrowthSeriesLimit", float(kGrowthSeriesLimit));
  out += "const int kGrowthTerms = " + std::to_string(kGrowthTerms) + ";\n";
  out += "const float kGrowthSeries[kGrowthTerms] = float[](";
  for (int k = 0; k < kGrowthTerms; ++k) {
    out += (k > 0 ? ", " : "") + literal(float(kGrowthSeries[k]));
  }
  out += ");\n";
  constant(out, "kLn2", float(kLn2));
  constant(out, "kLog2e", float(kLog2e));
  // sin_cos_det<double> and atan2_det<double> (det_trig.glsl.in, in planet_shading.glsl: a
  // planet's background), under the names the terrain stages' prelude gives their floats.
  using Trig = det_math_detail::TrigTerms<double>;
  std::vector<double> atan(Trig::kAtan);
  for (int k = 0; k < Trig::kAtan; ++k) {  // atan_reduced's Real(+-1) / Real(2k + 1)
    atan[k] = (k % 2 == 0 ? 1.0 : -1.0) / double(2 * k + 1);
  }
  double_series(out, "RELIEF_SIN", {det_math_detail::kSinCoeffs, Trig::kSin});
  double_series(out, "RELIEF_COS", {det_math_detail::kCosCoeffs, Trig::kCos});
  double_series(out, "RELIEF_ATAN", atan);
  using Pieces = det_math_detail::HalfPiPieces<double>;
  constant_double(out, "RELIEF_HALF_PI_HI", Pieces::hi);
  constant_double(out, "RELIEF_HALF_PI_MID", Pieces::mid);
  constant_double(out, "RELIEF_HALF_PI_LO", Pieces::lo);
  constant_double(out, "RELIEF_INV_HALF_PI", 1.0 / det_math_detail::kHalfPi);
  constant_double(out, "RELIEF_HALF_PI", det_math_detail::kHalfPi);
  constant_double(out, "RELIEF_QUARTER_PI", det_math_detail::kQuarterPi);
  constant_double(out, "RELIEF_TAN_EIGHTH_PI", det_math_detail::kTanEighthPi);
  constant_double(out, "RELIEF_PI", 2.0 * det_math_detail::kHalfPi);
  out += kGlRoundedGlsl;  // divide, square_root: the GL's own (glsl_rounding.h)
  return out;
}

std::vector<GlslSource> terrain_vertex_sources() {
  return with_prelude({{"terrain.vert", glsl::kTerrainVert}});
}

std::vector<GlslSource> terrain_fragment_sources() {
  std::vector<GlslSource> sources = shading_sources();
  sources.push_back({"terrain.frag", glsl::kTerrainFrag});
  return with_prelude(std::move(sources));
}

std::vector<GlslSource> background_vertex_sources() {
  return with_prelude({{"background.vert", glsl::kBackgroundVert}});
}

std::vector<GlslSource> background_fragment_sources() {
  std::vector<GlslSource> sources = shading_sources();
  sources.push_back({"background.frag", glsl::kBackgroundFrag});
  return with_prelude(std::move(sources));
}

std::vector<GlslSource> triangle_index_sources() {
  return with_prelude({{"triangles.comp", glsl::kTriangles}});
}

}  // namespace relief::gpu
