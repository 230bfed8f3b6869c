#include "gpu/gl_shader_prelude.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "core/det_math.h"
#include "core/limits.h"
#include "core/vertex_culling.h"
#include "gpu/glsl_rounding.h"

namespace relief::gpu {

namespace {

std::string define(const std::string& name, long long value) {
  return "#define " + name + " " + std::to_string(value) + "\n";
}

// The float's exact bits: GLSL has no hexadecimal float literal.
std::string define_float(const std::string& name, float value) {
  char bits[16];
  std::snprintf(bits, sizeof bits, "0x%08xu", std::bit_cast<std::uint32_t>(value));
  return "#define " + name + " uintBitsToFloat(" + bits + ")\n";
}

// A series' coefficients as RELIEF_<name>_COEFF[RELIEF_<name>_TERMS], each the float's bits.
std::string float_series(const std::string& name, const std::vector<float>& values) {
  std::string s = "const int " + name + "_TERMS = " + std::to_string(values.size()) + ";\n";
  s += "const float " + name + "_COEFF[" + std::to_string(values.size()) + "] = float[](";
  for (std::size_t k = 0; k < values.size(); ++k) {
    char bits[40];
    std::snprintf(bits, sizeof bits, "%suintBitsToFloat(0x%08xu)", k > 0 ? ", " : "",
                  std::bit_cast<std::uint32_t>(values[k]));
    s += bits;
  }
  return s + ");\n";
}

}  // namespace

std::string_view gl_stream_name(GlStream stream) {
  switch (stream) {
    case GlStream::kDx:
      return "dx";
    case GlStream::kDz:
      return "dz";
    case GlStream::kSigma:
      return "sigma";
    case GlStream::kNu:
      return "nu";
    case GlStream::kValid:
      return "valid";
    case GlStream::kHeight:
      return "height";
    case GlStream::kNx:
      return "nx";
    case GlStream::kNy:
      return "ny";
    case GlStream::kNz:
      return "nz";
    case GlStream::kSlope:
      return "slope";
    case GlStream::kWaterDepth:
      return "water_depth";
    case GlStream::kBentX:
      return "bent_x";
    case GlStream::kBentY:
      return "bent_y";
    case GlStream::kBentZ:
      return "bent_z";
    case GlStream::kBentDrop:
      return "bent_drop";
  }
  return "?";
}

std::string shader_prelude() {
  std::string s = "#version 450 core\n";
  s += define("RELIEF_MAX_OCTAVES", limits::kMaxOctaves);
  s += define("RELIEF_MAX_FIELD_LEVELS", limits::kMaxFieldLevels);
  s += define("RELIEF_GROUP_SIZE", kGroupSize);
  s += "#define RELIEF_NEED_DRAW " + std::to_string(int(kDraw)) + "u\n";
  s += define("RELIEF_BINDING_PARAMS", kBindingParams);
  s += define("RELIEF_BINDING_ROWS", kBindingRows);
  s += define("RELIEF_BINDING_LATTICE", kBindingLattice);
  s += define("RELIEF_BINDING_MASK", kBindingMask);
  s += define("RELIEF_BINDING_REACH", kBindingReach);
  s += define("RELIEF_BINDING_SKETCH", kBindingSketch);
  s += define("RELIEF_BINDING_PLANET", kBindingPlanet);
  for (const GlStream stream : kGlStreams) {
    std::string name(gl_stream_name(stream));
    for (char& c : name) {
      c = c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    }
    s += define("RELIEF_BINDING_" + name, stream_binding(stream));
  }
  // The constants of the float stages, as the CPU rounds them (Real(double) once).
  s += define_float("RELIEF_MIN_RAY_DESCENT", float(limits::kMinRayDescent));
  using Bits = det_math_detail::FloatBits<float>;
  s += define_float("RELIEF_FLT_MIN", Bits::kMinNormal);
  s += define_float("RELIEF_SUBNORMAL_SCALE", Bits::kSubnormalScale);
  s += define("RELIEF_SUBNORMAL_SHIFT", Bits::kSubnormalShift);
  s += define_float("RELIEF_SQRT2", float(1.4142135623730951));
  static_assert(Bits::kTerms == 5, "det_math.glsl spells out five series terms");
  for (int k = 0; k < Bits::kTerms; ++k) {
    s += define_float("RELIEF_LOG2_COEFF_" + std::to_string(k),
                      float(det_math_detail::kAtanhLog2Coeffs[k]));
  }
  // sin_cos_det<float> and atan2_det<float> (det_trig.glsl.in, in det_math.glsl), the
  // constants as the CPU rounds them: Real(double) once, and the atan series' float(+-1) /
  // float(2k + 1).
  using Trig = det_math_detail::TrigTerms<float>;
  std::vector<float> sin(Trig::kSin), cos(Trig::kCos), atan(Trig::kAtan);
  for (int k = 0; k < Trig::kSin; ++k) {
    sin[k] = float(det_math_detail::kSinCoeffs[k]);
  }
  for (int k = 0; k < Trig::kCos; ++k) {
    cos[k] = float(det_math_detail::kCosCoeffs[k]);
  }
  for (int k = 0; k < Trig::kAtan; ++k) {
    atan[k] = float(k % 2 == 0 ? 1.0 : -1.0) / float(2 * k + 1);
  }
  s += float_series("RELIEF_SIN", sin);
  s += float_series("RELIEF_COS", cos);
  s += float_series("RELIEF_ATAN", atan);
  using Pieces = det_math_detail::HalfPiPieces<float>;
  s += define_float("RELIEF_HALF_PI_HI", Pieces::hi);
  s += define_float("RELIEF_HALF_PI_MID", Pieces::mid);
  s += define_float("RELIEF_HALF_PI_LO", Pieces::lo);
  s += define_float("RELIEF_INV_HALF_PI", float(1.0 / det_math_detail::kHalfPi));
  s += define_float("RELIEF_TAN_EIGHTH_PI", float(det_math_detail::kTanEighthPi));
  s += define_float("RELIEF_QUARTER_PI", float(det_math_detail::kQuarterPi));
  s += define_float("RELIEF_HALF_PI", float(det_math_detail::kHalfPi));
  s += define_float("RELIEF_PI", float(2.0 * det_math_detail::kHalfPi));
  s += kCorrectlyRoundedGlsl;  // divide, square_root: correctly rounded (glsl_rounding.h)
  return s;
}

}  // namespace relief::gpu
