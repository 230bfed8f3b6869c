// log2_det of core/det_math.h, operation by operation: the exponent from the bits, the
// mantissa folded into [sqrt(1/2), sqrt(2)), then 2/ln2 atanh((m - 1)/(m + 1)) by Horner's rule
// in y^2. GLSL's built-in log2 is not used: the GLSL 4.50 specification allows it 3 ULP outside
// [0.5, 2] and an absolute error of 2^-21 inside, and each driver rounds it its own way. Every
// operation here is precise (no FMA contraction); its result equals the CPU's where division is
// correctly rounded (docs/gl-backend.md). The constants are the CPU's floats, set bit for bit
// by the prelude: RELIEF_LOG2_COEFF_0 .. 4, RELIEF_SQRT2, RELIEF_FLT_MIN and the subnormal
// scaling.
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
  precise float y = (m - 1.0) / (m + 1.0);  // |y| <= 0.1716; m + 1 >= 1.7
  precise float y2 = y * y;
  precise float series = RELIEF_LOG2_COEFF_4;
  series = series * y2 + RELIEF_LOG2_COEFF_3;
  series = series * y2 + RELIEF_LOG2_COEFF_2;
  series = series * y2 + RELIEF_LOG2_COEFF_1;
  series = series * y2 + RELIEF_LOG2_COEFF_0;
  precise float result = e + y * series;
  return result;
}

// sin_cos_det of core/det_math.h, operation by operation (docs/planet.md: every backend bends
// alike): k = round(x / (pi/2)) clamped to [-64, 64], r = x - k pi/2 in Cody and Waite's three
// pieces (RELIEF_HALF_PI_HI, _MID, _LO: k * hi and k * mid are exact), the Taylor series of sin
// and cos of r by Horner's rule in r^2 (RELIEF_SIN_COEFF_0 .. 4, RELIEF_COS_COEFF_0 .. 5), and
// the quadrant k mod 4 picks and negates them. GLSL's sin and cos are not used: the
// specification leaves their precision to the driver.
void sin_cos_det(float x, out float sine, out float cosine) {
  precise float q = x * RELIEF_INV_HALF_PI;
  q = q < -64.0 ? -64.0 : (q > 64.0 ? 64.0 : q);  // the conversion's domain
  precise float rounded = q < 0.0 ? q - 0.5 : q + 0.5;
  const int k = int(rounded);  // truncation toward zero, as C++'s static_cast<int>
  precise float fk = float(k);
  precise float r = ((x - fk * RELIEF_HALF_PI_HI) - fk * RELIEF_HALF_PI_MID) - fk * RELIEF_HALF_PI_LO;
  precise float r2 = r * r;
  precise float ps = RELIEF_SIN_COEFF_4;
  ps = ps * r2 + RELIEF_SIN_COEFF_3;
  ps = ps * r2 + RELIEF_SIN_COEFF_2;
  ps = ps * r2 + RELIEF_SIN_COEFF_1;
  ps = ps * r2 + RELIEF_SIN_COEFF_0;
  precise float pc = RELIEF_COS_COEFF_5;
  pc = pc * r2 + RELIEF_COS_COEFF_4;
  pc = pc * r2 + RELIEF_COS_COEFF_3;
  pc = pc * r2 + RELIEF_COS_COEFF_2;
  pc = pc * r2 + RELIEF_COS_COEFF_1;
  pc = pc * r2 + RELIEF_COS_COEFF_0;
  precise float s = r * ps;
  const int quadrant = k & 3;  // two's complement, as C++'s k & 3
  if (quadrant == 0) {
    sine = s;
    cosine = pc;
  } else if (quadrant == 1) {
    sine = pc;
    cosine = -s;
  } else if (quadrant == 2) {
    sine = -s;
    cosine = -pc;
  } else {
    sine = -pc;
    cosine = s;
  }
}

float sin_det(float x) {
  float s, c;
  sin_cos_det(x, s, c);
  return s;
}

// atan(u) for |u| <= tan(pi/8): the odd series, Horner in u^2 (RELIEF_ATAN_COEFF_0 .. 9 are
// the CPU's float(+-1) / float(2k + 1)).
float atan_reduced(float u) {
  precise float u2 = u * u;
  precise float series = RELIEF_ATAN_COEFF_9;
  series = series * u2 + RELIEF_ATAN_COEFF_8;
  series = series * u2 + RELIEF_ATAN_COEFF_7;
  series = series * u2 + RELIEF_ATAN_COEFF_6;
  series = series * u2 + RELIEF_ATAN_COEFF_5;
  series = series * u2 + RELIEF_ATAN_COEFF_4;
  series = series * u2 + RELIEF_ATAN_COEFF_3;
  series = series * u2 + RELIEF_ATAN_COEFF_2;
  series = series * u2 + RELIEF_ATAN_COEFF_1;
  series = series * u2 + RELIEF_ATAN_COEFF_0;
  precise float result = u * series;
  return result;
}

// atan2_det of core/det_math.h for y >= 0 and finite x: the angle in [0, pi] from the +x
// axis; 0 for (0, 0). Above tan(pi/8), atan t = pi/4 + atan((t - 1) / (t + 1)).
float atan2_det(float y, float x) {
  const float ax = x < 0.0 ? -x : x;
  const float lo = ax < y ? ax : y;
  const float hi = ax < y ? y : ax;
  if (!(hi > 0.0)) {
    return 0.0;  // (0, 0), and the domain guard of the division below
  }
  precise float t = lo / hi;  // [0, 1]
  precise float a;
  if (t > RELIEF_TAN_EIGHTH_PI) {
    precise float u = (t - 1.0) / (t + 1.0);
    a = RELIEF_QUARTER_PI + atan_reduced(u);
  } else {
    a = atan_reduced(t);
  }
  if (y > ax) {
    a = RELIEF_HALF_PI - a;
  }
  if (x < 0.0) {
    a = RELIEF_PI - a;
  }
  return a;
}
