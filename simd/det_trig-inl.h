// Per-target atan2_det and sin_cos_det of core/det_math.h, for float or double lanes (the
// lanes' type is the scalar code's Real): the same + - * / in the same order, the branches on
// the argument (the octant folds, the quadrant) as masks, so every lane returns the scalar
// bits on every target. Used by the planet's stage 2 (float), its bend (float) and its
// background (double).
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_DET_TRIG_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_DET_TRIG_INL_H_
#undef RELIEF_SIMD_DET_TRIG_INL_H_
#else
#define RELIEF_SIMD_DET_TRIG_INL_H_
#endif

#include <hwy/highway.h>

#include "core/det_math.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// atan_reduced<Real> (core/det_math.h): the odd series, Horner in u^2, its coefficients
// +-1 / (2k + 1) divided in Real as the scalar code's Real(+-1) / Real(2k + 1) (in float, not
// the double quotient rounded to float: that could round twice).
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE VD AtanReducedLanes(DD dd, VD u) {
  using Real = hn::TFromD<DD>;
  constexpr int n = det_math_detail::TrigTerms<Real>::kAtan;
  const VD u2 = hn::Mul(u, u);
  VD series = hn::Set(dd, Real((n - 1) % 2 == 0 ? 1.0 : -1.0) / Real(2 * (n - 1) + 1));
  for (int k = n - 2; k >= 0; --k) {
    series =
        hn::Add(hn::Mul(series, u2), hn::Set(dd, Real(k % 2 == 0 ? 1.0 : -1.0) / Real(2 * k + 1)));
  }
  return hn::Mul(u, series);
}

// atan2_det<Real>(y, x) (core/det_math.h) per lane, its branches as masks; y >= 0.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE VD Atan2Lanes(DD dd, VD y, VD x) {
  using namespace det_math_detail;
  using Real = hn::TFromD<DD>;
  const VD zero = hn::Zero(dd), one = hn::Set(dd, Real(1));
  const VD ax = hn::IfThenElse(hn::Lt(x, zero), hn::Neg(x), x);  // -0 stays -0, as there
  const auto ax_below = hn::Lt(ax, y);
  const VD lo = hn::IfThenElse(ax_below, ax, y);
  const VD hi = hn::IfThenElse(ax_below, y, ax);
  const auto defined = hn::Gt(hi, zero);  // (0, 0) and NaN: 0
  const VD t = hn::Div(lo, hn::IfThenElse(defined, hi, one));
  const auto big = hn::Gt(t, hn::Set(dd, Real(kTanEighthPi)));
  const VD u = hn::IfThenElse(big, hn::Div(hn::Sub(t, one), hn::Add(t, one)), t);
  const VD series = AtanReducedLanes(dd, u);
  VD a = hn::IfThenElse(big, hn::Add(hn::Set(dd, Real(kQuarterPi)), series), series);
  a = hn::IfThenElse(hn::Gt(y, ax), hn::Sub(hn::Set(dd, Real(kHalfPi)), a), a);
  a = hn::IfThenElse(hn::Lt(x, zero), hn::Sub(hn::Set(dd, Real(2.0 * kHalfPi)), a), a);
  return hn::IfThenElseZero(defined, a);
}

// sin_cos_det<Real> (core/det_math.h) per lane for finite x: the quadrant k = round(x / (pi/2))
// clamped to +-64 (as the scalar code's int), kept as an exact Real; the reduction in three
// pieces; the series; k mod 4 picks and negates.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE void SinCosLanes(DD dd, VD x, VD& sine, VD& cosine) {
  using namespace det_math_detail;
  using Real = hn::TFromD<DD>;
  using Pieces = HalfPiPieces<Real>;
  const VD zero = hn::Zero(dd), half = hn::Set(dd, Real(0.5));
  VD q = hn::Mul(x, hn::Set(dd, Real(1.0 / kHalfPi)));
  const VD limit = hn::Set(dd, Real(64)), neg_limit = hn::Set(dd, Real(-64));
  q = hn::IfThenElse(hn::Lt(q, neg_limit), neg_limit, hn::IfThenElse(hn::Gt(q, limit), limit, q));
  // int(q -+ 0.5) truncates toward zero: Trunc gives the same integer, exact in Real.
  const VD k = hn::Trunc(hn::IfThenElse(hn::Lt(q, zero), hn::Sub(q, half), hn::Add(q, half)));
  const VD r = hn::Sub(hn::Sub(hn::Sub(x, hn::Mul(k, hn::Set(dd, Pieces::hi))),
                               hn::Mul(k, hn::Set(dd, Pieces::mid))),
                       hn::Mul(k, hn::Set(dd, Pieces::lo)));
  const VD r2 = hn::Mul(r, r);
  constexpr int kSin = TrigTerms<Real>::kSin, kCos = TrigTerms<Real>::kCos;
  VD ps = hn::Set(dd, Real(kSinCoeffs[kSin - 1]));
  for (int i = kSin - 2; i >= 0; --i) {
    ps = hn::Add(hn::Mul(ps, r2), hn::Set(dd, Real(kSinCoeffs[i])));
  }
  VD pc = hn::Set(dd, Real(kCosCoeffs[kCos - 1]));
  for (int i = kCos - 2; i >= 0; --i) {
    pc = hn::Add(hn::Mul(pc, r2), hn::Set(dd, Real(kCosCoeffs[i])));
  }
  const VD s = hn::Mul(r, ps), c = pc;
  // k & 3 of the integer k (two's complement): k - 4 floor(k / 4), exact for |k| <= 64.
  const VD quadrant =
      hn::Sub(k, hn::Mul(hn::Set(dd, Real(4)), hn::Floor(hn::Mul(k, hn::Set(dd, Real(0.25))))));
  const auto q1 = hn::Eq(quadrant, hn::Set(dd, Real(1)));
  const auto q2 = hn::Eq(quadrant, hn::Set(dd, Real(2)));
  const auto q3 = hn::Eq(quadrant, hn::Set(dd, Real(3)));
  sine = hn::IfThenElse(q1, c, hn::IfThenElse(q2, hn::Neg(s), hn::IfThenElse(q3, hn::Neg(c), s)));
  cosine = hn::IfThenElse(q1, hn::Neg(s), hn::IfThenElse(q2, hn::Neg(c), hn::IfThenElse(q3, s, c)));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
