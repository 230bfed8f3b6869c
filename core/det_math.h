// Deterministic elementary functions: results depend only on IEEE-754 basic operations
// (+ - * /, exact bit manipulation), so every compiler, libm and SIMD target that rounds to
// nearest produces the same bits. Library log/exp use target-specific polynomials and FMA
// (docs/architecture.md, Determinism) and may not be used inside stages.
#pragma once

#include <bit>
#include <cstdint>
#include <type_traits>

namespace relief {

namespace det_math_detail {

template <class Real>
struct FloatBits;

template <>
struct FloatBits<float> {
  using Int = std::uint32_t;
  static constexpr int kMantissaBits = 23;
  static constexpr int kExponentBias = 127;
  static constexpr Int kExponentMask = 0xffu;
  static constexpr Int kOneBits = 0x3f800000u;  // bits of 1.0f
  // atanh series terms 2/(k ln 2), k = 1, 3, ..., 9: the next term is below 2^-26 of the sum
  // because |y| <= 3 - 2 sqrt(2) = 0.1716 (y^10/11 < 2.4e-9).
  static constexpr int kTerms = 5;
  static constexpr float kMinNormal = 1.17549435e-38f;   // 2^-126
  static constexpr float kSubnormalScale = 16777216.0f;  // 2^24 lifts every subnormal
  static constexpr int kSubnormalShift = 24;
};

template <>
struct FloatBits<double> {
  using Int = std::uint64_t;
  static constexpr int kMantissaBits = 52;
  static constexpr int kExponentBias = 1023;
  static constexpr Int kExponentMask = 0x7ffu;
  static constexpr Int kOneBits = 0x3ff0000000000000ull;
  // k = 1, ..., 23: y^24/25 < 6e-20, below 2^-54 of the sum.
  static constexpr int kTerms = 12;
  static constexpr double kMinNormal = 2.2250738585072014e-308;  // 2^-1022
  static constexpr double kSubnormalScale = 9007199254740992.0;  // 2^53
  static constexpr int kSubnormalShift = 53;
};

// 2 / (k ln 2) for k = 1, 3, 5, ...; written as literals so that float and double get
// correctly rounded constants without any run-time evaluation.
inline constexpr double kAtanhLog2Coeffs[12] = {
    2.8853900817779268,  0.9617966939259757,  0.5770780163555853, 0.41219858311113244,
    0.3205988979753252,  0.2623081892525388,  0.2219530832136867, 0.19235933878519512,
    0.16972882833987804, 0.15186263588304877, 0.1373995277037108, 0.12545174268599682};

}  // namespace det_math_detail

// log2(x) for finite x > 0 (normal or subnormal), within 3 ulp (float) or 2 ulp (double)
// of the true value (det_math_test.cc measures 2.4 and 1.0).
// Domain: the caller guarantees x > 0 and finite; other inputs give an unspecified finite
// value (never NaN), so a violated precondition cannot poison a buffer.
// Method: x = m 2^e with m in [sqrt(1/2), sqrt(2)); log2 m = 2/ln2 atanh((m-1)/(m+1)),
// the odd series evaluated by Horner's rule in y^2 (a fixed order of correctly rounded ops).
template <class Real>
Real log2_det(Real x) {
  static_assert(std::is_floating_point_v<Real>);
  using B = det_math_detail::FloatBits<Real>;
  using Int = typename B::Int;
  Real exponent_adjust = 0;
  // Subnormals: scale into the normal range first (multiplication by a power of two is exact).
  if (x < B::kMinNormal) {
    x = x * B::kSubnormalScale;
    exponent_adjust = Real(-B::kSubnormalShift);
  }
  const Int bits = std::bit_cast<Int>(x);
  const Int biased = (bits >> B::kMantissaBits) & B::kExponentMask;
  Real e = Real(static_cast<int>(biased) - B::kExponentBias) + exponent_adjust;
  const Int mantissa = bits & ((Int(1) << B::kMantissaBits) - 1);
  Real m = std::bit_cast<Real>(mantissa | B::kOneBits);  // [1, 2)
  if (m > Real(1.4142135623730951)) {
    m = m * Real(0.5);
    e = e + Real(1);
  }
  const Real y = (m - Real(1)) / (m + Real(1));  // |y| <= 0.1716; m + 1 >= 1.7
  const Real y2 = y * y;
  Real series = Real(det_math_detail::kAtanhLog2Coeffs[B::kTerms - 1]);
  for (int k = B::kTerms - 2; k >= 0; --k) {
    series = series * y2 + Real(det_math_detail::kAtanhLog2Coeffs[k]);
  }
  return e + y * series;
}

// Natural logarithm for finite x > 0 (same domain as log2_det), one more rounding.
template <class Real>
Real log_det(Real x) {
  return log2_det(x) * Real(0.69314718055994531);
}

namespace det_math_detail {

// (ln 2)^k / k!, k = 0..13: the Taylor series of 2^f = e^(f ln 2).
inline constexpr double kExp2Coeffs[14] = {1.0,
                                           0.6931471805599453,
                                           0.2402265069591007,
                                           0.055504108664821576,
                                           0.009618129107628477,
                                           0.0013333558146428441,
                                           0.00015403530393381606,
                                           1.5252733804059838e-05,
                                           1.3215486790144305e-06,
                                           1.0178086009239696e-07,
                                           7.054911620801121e-09,
                                           4.44553827187081e-10,
                                           2.5678435993488196e-11,
                                           1.3691488853904124e-12};

template <class Real>
struct Exp2Terms;
template <>
struct Exp2Terms<float> {
  // |f| <= 1/2: (ln2/2)^9 / 9! < 2e-10, below 2^-25.
  static constexpr int kTerms = 9;
};
template <>
struct Exp2Terms<double> {
  // (ln2/2)^14 / 14! < 4e-18, below 2^-54.
  static constexpr int kTerms = 14;
};

}  // namespace det_math_detail

// 2^x for finite x, within 2 ulp, from + - * and exact bit manipulation only. Domain: x in
// [-125, 125] for float, [-1021, 1021] for double; outside it the argument is clamped to the
// domain's end (the result then under- or overflows gracefully to a tiny or huge finite value,
// never to 0, infinity or NaN), which keeps every stage that exponentiates total.
// Method: n = round(x) by the 1.5 * 2^52 trick, f = x - n in [-1/2, 1/2], 2^f by Horner on
// its Taylor series, times 2^n built in the exponent field.
template <class Real>
Real exp2_det(Real x) {
  static_assert(std::is_floating_point_v<Real>);
  using B = det_math_detail::FloatBits<Real>;
  using Int = typename B::Int;
  const Real limit = Real(B::kExponentBias - 2);
  x = x < -limit ? -limit : (x > limit ? limit : x);
  const double magic = 6755399441055744.0;  // 1.5 * 2^52: rounds to the nearest integer
  const Real n = Real((double(x) + magic) - magic);
  const Real f = x - n;
  constexpr int kTerms = det_math_detail::Exp2Terms<Real>::kTerms;
  Real series = Real(det_math_detail::kExp2Coeffs[kTerms - 1]);
  for (int k = kTerms - 2; k >= 0; --k) {
    series = series * f + Real(det_math_detail::kExp2Coeffs[k]);
  }
  const Int exponent = static_cast<Int>(static_cast<int>(n) + B::kExponentBias) << B::kMantissaBits;
  return series * std::bit_cast<Real>(exponent);
}

namespace det_math_detail {

// (-1)^k / (2k+1)! and (-1)^k / (2k)!: the Taylor series of sin and cos.
inline constexpr double kSinCoeffs[8] = {1.0,
                                         -0.16666666666666666,
                                         0.008333333333333333,
                                         -0.0001984126984126984,
                                         2.7557319223985893e-06,
                                         -2.505210838544172e-08,
                                         1.6059043836821613e-10,
                                         -7.647163731819816e-13};
inline constexpr double kCosCoeffs[9] = {1.0,
                                         -0.5,
                                         0.041666666666666664,
                                         -0.001388888888888889,
                                         2.48015873015873e-05,
                                         -2.755731922398589e-07,
                                         2.08767569878681e-09,
                                         -1.1470745597729725e-11,
                                         4.779477332387385e-14};

template <class Real>
struct TrigTerms;
template <>
struct TrigTerms<float> {
  // |r| <= pi/4: r^11/11! < 2e-9 and r^12/12! < 2e-10, below 2^-25 of the result.
  static constexpr int kSin = 5, kCos = 6;
  // |u| <= tan(pi/8): u^20/21 < 1e-9 of u.
  static constexpr int kAtan = 10;
};
template <>
struct TrigTerms<double> {
  // r^17/17! < 5e-17, r^18/18! < 3e-18: below 2^-54 of the result.
  static constexpr int kSin = 8, kCos = 9;
  // u^42/43 < 2e-18 of u.
  static constexpr int kAtan = 21;
};

// pi/2 in three pieces (Cody and Waite): hi and mid have few enough bits that k * hi and
// k * mid are exact for |k| <= 64, so x - k pi/2 loses nothing to cancellation near a
// multiple of pi/2 (float: 8 + 17 + 24 bits, double: 33 + 33 + 53).
template <class Real>
struct HalfPiPieces;
template <>
struct HalfPiPieces<float> {
  static constexpr float hi = 1.5703125f, mid = 0.00048382580280303955f,
                         lo = 9.920935796805404e-10f;
};
template <>
struct HalfPiPieces<double> {
  static constexpr double hi = 1.5707963267341256, mid = 6.077100506303966e-11,
                          lo = 2.0222662487959506e-21;
};
inline constexpr double kHalfPi = 1.5707963267948966;
inline constexpr double kQuarterPi = 0.78539816339744831;
inline constexpr double kTanEighthPi = 0.41421356237309505;  // tan(pi/8)

// sin and cos of |r| <= pi/4 (plus rounding), Horner in r^2.
template <class Real>
void sin_cos_reduced(Real r, Real& s, Real& c) {
  const Real r2 = r * r;
  Real ps = Real(kSinCoeffs[TrigTerms<Real>::kSin - 1]);
  for (int k = TrigTerms<Real>::kSin - 2; k >= 0; --k) {
    ps = ps * r2 + Real(kSinCoeffs[k]);
  }
  Real pc = Real(kCosCoeffs[TrigTerms<Real>::kCos - 1]);
  for (int k = TrigTerms<Real>::kCos - 2; k >= 0; --k) {
    pc = pc * r2 + Real(kCosCoeffs[k]);
  }
  s = r * ps;
  c = pc;
}

// atan(u) for |u| <= tan(pi/8) (plus rounding): the odd series, Horner in u^2.
template <class Real>
Real atan_reduced(Real u) {
  const Real u2 = u * u;
  constexpr int n = TrigTerms<Real>::kAtan;
  Real series = Real((n - 1) % 2 == 0 ? 1.0 : -1.0) / Real(2 * (n - 1) + 1);
  for (int k = n - 2; k >= 0; --k) {
    series = series * u2 + Real(k % 2 == 0 ? 1.0 : -1.0) / Real(2 * k + 1);
  }
  return u * series;
}

}  // namespace det_math_detail

// sin(x) and cos(x) for |x| <= 64, within 3 ulp of the true values (2.3 measured on [-8, 8]
// by tests/core/planet_geometry_test.cc), also near the zeros (sin(x) for tiny x is x).
// Outside the domain the reduction loses accuracy but the results stay finite in [-1, 1].
// Method: k = round(x / (pi/2)), r = x - k pi/2 in three pieces, the Taylor series of sin and
// cos of r, and the quadrant k mod 4 picks and negates them. Used by the planet's bend
// (core/planet_bend.h) and stage 2 on the sphere, so every backend bends alike.
template <class Real>
void sin_cos_det(Real x, Real& sine, Real& cosine) {
  static_assert(std::is_floating_point_v<Real>);
  using namespace det_math_detail;
  Real q = x * Real(1.0 / kHalfPi);
  q = q < Real(-64) ? Real(-64) : (q > Real(64) ? Real(64) : q);  // the conversion's domain
  const int k = static_cast<int>(q < Real(0) ? q - Real(0.5) : q + Real(0.5));  // round
  using Pieces = HalfPiPieces<Real>;
  const Real r = ((x - Real(k) * Pieces::hi) - Real(k) * Pieces::mid) - Real(k) * Pieces::lo;
  Real s, c;
  sin_cos_reduced(r, s, c);
  switch (k & 3) {
    case 0:
      sine = s, cosine = c;
      return;
    case 1:
      sine = c, cosine = -s;
      return;
    case 2:
      sine = -s, cosine = -c;
      return;
    default:
      sine = -c, cosine = s;
      return;
  }
}

template <class Real>
Real sin_det(Real x) {
  Real s, c;
  sin_cos_det(x, s, c);
  return s;
}

// atan2(y, x) for y >= 0 and any finite x: the angle in [0, pi] between (x, y) and the +x
// axis, within 3.5 ulp (2.97 measured by tests/core/planet_geometry_test.cc); 0 for (0, 0). (Relief
// only needs angles from a downward or horizontal axis, so y is a length.) Method: t =
// min / max of |x| and y in [0, 1]; above tan(pi/8), atan t = pi/4 + atan((t - 1) / (t + 1));
// the series; then pi/2 - a where y > |x|, pi - a where x < 0.
template <class Real>
Real atan2_det(Real y, Real x) {
  static_assert(std::is_floating_point_v<Real>);
  using namespace det_math_detail;
  const Real ax = x < Real(0) ? -x : x;
  const Real lo = ax < y ? ax : y;
  const Real hi = ax < y ? y : ax;
  if (!(hi > Real(0))) {
    return Real(0);  // (0, 0), and the domain guard of the division below
  }
  const Real t = lo / hi;  // [0, 1]
  Real a;
  if (t > Real(kTanEighthPi)) {
    a = Real(kQuarterPi) + atan_reduced((t - Real(1)) / (t + Real(1)));
  } else {
    a = atan_reduced(t);
  }
  if (y > ax) {
    a = Real(kHalfPi) - a;
  }
  if (x < Real(0)) {
    a = Real(2.0 * kHalfPi) - a;
  }
  return a;
}

}  // namespace relief
