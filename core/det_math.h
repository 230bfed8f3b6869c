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

}  // namespace relief
