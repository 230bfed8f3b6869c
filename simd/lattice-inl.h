// Per-target building blocks shared by the kernels that sample the noise lattice: the
// periodic wrap, the fade curves and S(px, pz) of core/interpolant.h, and the exact products
// of core/octave_coordinates.h, each written with the scalar code's operations in its order.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_LATTICE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_LATTICE_INL_H_
#undef RELIEF_SIMD_LATTICE_INL_H_
#else
#define RELIEF_SIMD_LATTICE_INL_H_
#endif

#include <hwy/highway.h>

#include "core/interpolant.h"
#include "simd/pair_gather-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// p - P floor(p / P): wrap_period (interpolant.h).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V WrapPeriod(D /*d*/, V p, V period, V inv_period) {
  return hn::Sub(p, hn::Mul(period, hn::Floor(hn::Mul(p, inv_period))));
}

// fade<kKind> (interpolant.h).
template <Interpolant kKind, class D, class V = hn::Vec<D>>
HWY_INLINE V Fade(D d, V t) {
  if constexpr (kKind == Interpolant::kLinear) {
    return t;
  } else if constexpr (kKind == Interpolant::kCubic) {
    return hn::Mul(hn::Mul(t, t), hn::Sub(hn::Set(d, 3.0f), hn::Mul(hn::Set(d, 2.0f), t)));
  } else {
    const V inner = hn::Add(hn::Mul(t, hn::Sub(hn::Mul(t, hn::Set(d, 6.0f)), hn::Set(d, 15.0f))),
                            hn::Set(d, 10.0f));
    return hn::Mul(hn::Mul(hn::Mul(t, t), t), inner);
  }
}

// The lattice of one frame as a kernel sees it: the values and the wrap.
struct LatticeView {
  const float* values;
  int shift;  // log2 P: row j starts at j << shift
  int mask;   // P - 1
  float period, inv_period;
};

inline LatticeView view_of(const NoiseLattice& lattice) {
  int shift = 0;
  while ((1 << shift) < lattice.size) {
    ++shift;
  }
  return {lattice.values.data(), shift, lattice.mask, float(lattice.size),
          1.0f / float(lattice.size)};
}

// The values at the four corners of the cells (i0, j0) .. (i1, j1) (indices already wrapped):
// where no lane's cell wraps in x (i1 = i0 + 1), each row's two corners are neighbours in
// memory, one 64-bit pair gather (AVX2, AVX3; simd/pair_gather-inl.h) instead of two.
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE void LatticeCorners(D d, const LatticeView& l, VI i0, VI i1, VI j0, VI j1, V& v00,
                               V& v10, V& v01, V& v11) {
  const VI row0 = hn::ShiftLeftSame(j0, l.shift);
  const VI row1 = hn::ShiftLeftSame(j1, l.shift);
#if RELIEF_PAIR_GATHER
  const hn::RebindToSigned<D> di;
  if (HWY_LIKELY(hn::AllFalse(di, hn::Eq(i0, hn::Set(di, l.mask))))) {
    GatherFloatPairs(l.values, hn::Add(row0, i0), v00, v10);
    GatherFloatPairs(l.values, hn::Add(row1, i0), v01, v11);
    return;
  }
#endif
  v00 = hn::GatherIndex(d, l.values, hn::Add(row0, i0));
  v10 = hn::GatherIndex(d, l.values, hn::Add(row0, i1));
  v01 = hn::GatherIndex(d, l.values, hn::Add(row1, i0));
  v11 = hn::GatherIndex(d, l.values, hn::Add(row1, i1));
}

// sample_lattice<kKind> (interpolant.h): locate_cell, four gathers, two lerps in x, one in z.
// `period` and `inv_period`: l.period and l.inv_period in every lane.
template <Interpolant kKind, class D, class V = hn::Vec<D>>
HWY_INLINE V SampleLattice(D d, const LatticeView& l, V period, V inv_period, V px, V pz) {
  const hn::RebindToSigned<D> di;
  const V wx = WrapPeriod(d, px, period, inv_period);
  const V wz = WrapPeriod(d, pz, period, inv_period);
  const V fx = hn::Floor(wx);
  const V fz = hn::Floor(wz);
  const auto mask = hn::Set(di, l.mask);
  const auto one = hn::Set(di, 1);
  const auto i0 = hn::And(hn::ConvertTo(di, fx), mask);  // fx in [0, P]: exact
  const auto j0 = hn::And(hn::ConvertTo(di, fz), mask);
  const auto i1 = hn::And(hn::Add(i0, one), mask);
  const auto j1 = hn::And(hn::Add(j0, one), mask);
  const V tx = Fade<kKind>(d, hn::Sub(wx, fx));
  const V tz = Fade<kKind>(d, hn::Sub(wz, fz));
  V v00, v10, v01, v11;
  LatticeCorners(d, l, i0, i1, j0, j1, v00, v10, v01, v11);
  const V bottom = hn::Add(v00, hn::Mul(tx, hn::Sub(v10, v00)));
  const V top = hn::Add(v01, hn::Mul(tx, hn::Sub(v11, v01)));
  return hn::Add(bottom, hn::Mul(tz, hn::Sub(top, bottom)));
}

// split_halves<float> (octave_coordinates.h).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void SplitHalves(D d, V a, V& hi, V& lo) {
  const V t = hn::Mul(hn::Set(d, 4097.0f), a);
  hi = hn::Sub(t, hn::Sub(t, a));
  lo = hn::Sub(a, hi);
}

// product_error (octave_coordinates.h): a * b - product exactly.
template <class V>
HWY_INLINE V ProductError(V a_hi, V a_lo, V b_hi, V b_lo, V product) {
  const V first = hn::Add(hn::Sub(hn::Mul(a_hi, b_hi), product), hn::Mul(a_hi, b_lo));
  return hn::Add(hn::Add(first, hn::Mul(a_lo, b_hi)), hn::Mul(a_lo, b_lo));
}

// sum_error (octave_coordinates.h): a + b - sum exactly (two-sum).
template <class V>
HWY_INLINE V SumError(V a, V b, V sum) {
  const V b_virtual = hn::Sub(sum, a);
  const V a_virtual = hn::Sub(sum, b_virtual);
  return hn::Add(hn::Sub(a, a_virtual), hn::Sub(b, b_virtual));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
