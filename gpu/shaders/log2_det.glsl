// log2_det of core/det_math.h, operation by operation: the exponent from the bits, the
// mantissa folded into [sqrt(1/2), sqrt(2)), then 2/ln2 atanh((m - 1)/(m + 1)) by Horner's rule
// in y^2. GLSL's built-in log2 is not used: the GLSL 4.50 specification allows it 3 ULP outside
// [0.5, 2] and an absolute error of 2^-21 inside, and each driver rounds it its own way. Every
// operation here is precise (no FMA contraction), and the division is the prelude's divide
// (gpu/glsl_rounding.h: correctly rounded in the compute stages, the GL's own in the draw): its
// result is the CPU's where that division is (docs/gl-backend.md). The constants are the
// CPU's floats, set bit for bit by the prelude: RELIEF_LOG2_COEFF_0 .. 4, RELIEF_SQRT2, RELIEF_FLT_MIN and the subnormal
// scaling; both preludes (gl_shader_prelude.cc for the compute stages, glsl_prelude.cc for
// the draw programs) define them, so that one source serves both.
float log2_det(float x_in) {
  precise float x = x_in;
  precise float exponent_adjust = 0.0;
  // Subnormals: scaled into the normal range first (exact). Unused by the stages (their
  // arguments are above kMinSpacingSq), and a driver that flushes subnormals to zero never
  // takes it.
  if (x < RELIEF_FLT_MIN) {
    x = x * RELIEF_SUBNORMAL_SCALE;
    exponent_adjust = -float(RELIEF_SUBNORMAL_SHIFT);
  }
  const uint bits = floatBitsToUint(x);
  const int biased = int((bits >> 23) & 0xffu);
  precise float e = float(biased - 127) + exponent_adjust;
  precise float m = uintBitsToFloat((bits & 0x7fffffu) | 0x3f800000u);  // [1, 2)
  if (m > RELIEF_SQRT2) {
    m = m * 0.5;
    e = e + 1.0;
  }
  precise float y = divide(m - 1.0, m + 1.0);  // |y| <= 0.1716; m + 1 >= 1.7
  precise float y2 = y * y;
  precise float series = RELIEF_LOG2_COEFF_4;
  series = series * y2 + RELIEF_LOG2_COEFF_3;
  series = series * y2 + RELIEF_LOG2_COEFF_2;
  series = series * y2 + RELIEF_LOG2_COEFF_1;
  series = series * y2 + RELIEF_LOG2_COEFF_0;
  precise float result = e + y * series;
  return result;
}
