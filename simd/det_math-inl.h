// Per-target log2_det and exp2_det of core/det_math.h for float, one argument per lane: the
// same + - * / and bit manipulation in the same order, so every lane returns the scalar bits
// on every target. Branches on the argument (subnormal scaling, the mantissa's fold into
// [sqrt(1/2), sqrt(2)), exp2's clamp) become masks.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_DET_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_DET_MATH_INL_H_
#undef RELIEF_SIMD_DET_MATH_INL_H_
#else
#define RELIEF_SIMD_DET_MATH_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "core/det_math.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// log2_det<float>: x = m 2^e, m folded into [sqrt(1/2), sqrt(2)), e + y series(y^2) with
// y = (m - 1) / (m + 1). Same domain as the scalar function (finite x > 0; anything else gives
// what the scalar code gives for it, through the same operations).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Log2Det(D d, V x) {
  using B = det_math_detail::FloatBits<float>;
  const hn::RebindToUnsigned<D> du;
  const hn::RebindToSigned<D> di;
  // Subnormals: scaled into the normal range first (exact), the exponent adjusted.
  const auto subnormal = hn::Lt(x, hn::Set(d, B::kMinNormal));
  x = hn::IfThenElse(subnormal, hn::Mul(x, hn::Set(d, B::kSubnormalScale)), x);
  const V exponent_adjust = hn::IfThenElseZero(subnormal, hn::Set(d, float(-B::kSubnormalShift)));
  const auto bits = hn::BitCast(du, x);
  const auto biased =
      hn::And(hn::ShiftRight<B::kMantissaBits>(bits), hn::Set(du, B::kExponentMask));
  // float(int(biased) - bias) + adjust: the integer difference is exact in float.
  V e = hn::Add(hn::ConvertTo(d, hn::Sub(hn::BitCast(di, biased), hn::Set(di, B::kExponentBias))),
                exponent_adjust);
  const auto mantissa = hn::And(bits, hn::Set(du, (std::uint32_t(1) << B::kMantissaBits) - 1));
  V m = hn::BitCast(d, hn::Or(mantissa, hn::Set(du, B::kOneBits)));  // [1, 2)
  const auto fold = hn::Gt(m, hn::Set(d, float(1.4142135623730951)));
  m = hn::IfThenElse(fold, hn::Mul(m, hn::Set(d, 0.5f)), m);
  e = hn::IfThenElse(fold, hn::Add(e, hn::Set(d, 1.0f)), e);
  const V one = hn::Set(d, 1.0f);
  const V y = hn::Div(hn::Sub(m, one), hn::Add(m, one));
  const V y2 = hn::Mul(y, y);
  V series = hn::Set(d, float(det_math_detail::kAtanhLog2Coeffs[B::kTerms - 1]));
  for (int k = B::kTerms - 2; k >= 0; --k) {
    series = hn::Add(hn::Mul(series, y2), hn::Set(d, float(det_math_detail::kAtanhLog2Coeffs[k])));
  }
  return hn::Add(e, hn::Mul(y, series));
}

// exp2_det<float>: clamp to [-125, 125], n = the nearest integer (ties to even), 2^(x - n) by
// Horner, times 2^n built in the exponent field.
// The scalar code rounds with the double constant 1.5 * 2^52: (double(x) + M) - M. Here the
// float constant 1.5 * 2^23 does it in float lanes with the same result bit for bit: for
// |x| <= 125, x + 1.5 * 2^23 lies in [2^23, 2^24) where floats are the integers, so the sum is
// 1.5 * 2^23 + round_to_nearest_even(x) exactly (as double(x) + M is M + that integer in
// double), and subtracting the constant again is exact in both (the integer, +0 for x = -0 in
// both). NaN stays NaN in both.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Exp2Det(D d, V x) {
  using B = det_math_detail::FloatBits<float>;
  const hn::RebindToSigned<D> di;
  const V limit = hn::Set(d, float(B::kExponentBias - 2));
  const V neg_limit = hn::Set(d, -float(B::kExponentBias - 2));
  // x < -limit ? -limit : (x > limit ? limit : x)
  x = hn::IfThenElse(hn::Lt(x, neg_limit), neg_limit, hn::IfThenElse(hn::Gt(x, limit), limit, x));
  const V magic = hn::Set(d, 12582912.0f);  // 1.5 * 2^23
  const V n = hn::Sub(hn::Add(x, magic), magic);
  const V f = hn::Sub(x, n);
  constexpr int kTerms = det_math_detail::Exp2Terms<float>::kTerms;
  V series = hn::Set(d, float(det_math_detail::kExp2Coeffs[kTerms - 1]));
  for (int k = kTerms - 2; k >= 0; --k) {
    series = hn::Add(hn::Mul(series, f), hn::Set(d, float(det_math_detail::kExp2Coeffs[k])));
  }
  const auto exponent =
      hn::ShiftLeft<B::kMantissaBits>(hn::Add(hn::ConvertTo(di, n), hn::Set(di, B::kExponentBias)));
  return hn::Mul(series, hn::BitCast(d, exponent));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
