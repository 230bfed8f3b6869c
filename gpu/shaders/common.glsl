// Helpers of stage 8 in GLSL, each the operation sequence of its C++ original (core/vec3.h,
// core/det_math.h), so that a conforming implementation with IEEE-754 float arithmetic
// computes the same bits. Every intermediate is `precise`: without it a GLSL compiler may
// contract a * b + c into FMA or reassociate sums, which the CPU code (-ffp-contract=off)
// never does. GLSL's own mix, smoothstep, clamp, min, max and dot are not used: their
// operation order (and NaN handling) is not specified, or differs from the CPU's.

// std::max(a, b) and std::min(a, b): the first argument unless the comparison says otherwise.
float max_cpp(float a, float b) { return (a < b) ? b : a; }
float min_cpp(float a, float b) { return (b < a) ? b : a; }

// core/vec3.h
float clamp01(float t) { return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t); }

float smooth01(float t_in) {
  precise float t = clamp01(t_in);
  precise float r = t * t * (3.0 - 2.0 * t);
  return r;
}

float dot3(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

vec3 lerp3(vec3 a, vec3 b, float t) {
  precise vec3 r = a + t * (b - a);
  return r;
}

// v / |v|, or `fallback` where |v|^2 is not a positive finite number (the sqrt's domain).
vec3 normalize_or(vec3 v, vec3 fallback) {
  precise float length_sq = dot3(v, v);
  if (!(length_sq > 0.0) || isinf(length_sq)) {
    return fallback;
  }
  precise float inv = divide(1.0, square_root(length_sq));
  precise vec3 r = v * inv;
  return r;
}

// log2_det: log2_det.glsl, shared with the compute stages.

// core/det_math.h: 2^x by Taylor's series of 2^f, f = x - round(x). The CPU rounds with the
// 1.5 * 2^52 trick in double, which for |x| <= 125 is round-half-even: roundEven, exact.
float exp2_det(float x_in) {
  precise float x = x_in < -kExp2Limit ? -kExp2Limit : (x_in > kExp2Limit ? kExp2Limit : x_in);
  precise float n = roundEven(x);
  precise float f = x - n;
  precise float series = kExp2Coeff[kExp2Terms - 1];
  for (int k = kExp2Terms - 2; k >= 0; --k) {
    series = series * f + kExp2Coeff[k];
  }
  const float scale = uintBitsToFloat(uint(int(n) + 127) << 23u);
  precise float r = series * scale;
  return r;
}
