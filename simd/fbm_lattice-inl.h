// Per-target lattice sampling for the fBm kernel (simd/fbm-inl.h): sample_lattice<kKind> of
// core/interpolant.h on a vector of points, bit for bit SampleLattice of simd/lattice-inl.h
// (the same floating-point operations in the same order per lane on the same values), with
// fewer operations:
//   - the cell: where every lane's coordinate p is at least 0 (and below 2^31), wrap_period
//     changes neither the fraction nor the column modulo P, so floor(p) gives both directly;
//     elsewhere the four operations of wrap_period first (SampleFbmLattice);
//   - the corners: where every lane lies in one lattice row, or in two neighbouring ones, and
//     within a short run of columns (neighbouring points of a grid row, an octave whose cells
//     are larger than the points' spacing), the corner values are lane permutations of one or
//     two vector loads per row, a window (WindowCorners), instead of four gathers of N lanes;
//   - elsewhere gathers, of (v00, v10) and (v01, v11) as 64-bit pairs where no lane's cell
//     wraps in x (GatherCorners): half the gathered elements.
// Only where the values come from differs, never how they are combined.
#if defined(RELIEF_SIMD_FBM_LATTICE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_FBM_LATTICE_INL_H_
#undef RELIEF_SIMD_FBM_LATTICE_INL_H_
#else
#define RELIEF_SIMD_FBM_LATTICE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/interpolant.h"
#include "core/lattice.h"
#include "simd/lattice-inl.h"
#include "simd/pair_gather-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

// The x86 targets: raw truncation (TruncateToInt), permutations and 64-bit gathers. Others
// (EMU128) wrap every coordinate and gather, as SampleLattice does.
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_SSSE3
#define RELIEF_FBM_X86 1
#else
#define RELIEF_FBM_X86 0
#endif

// The windows per target (N lanes). kTwoTables (AVX3): 2N columns from a multiple of N, two
// aligned loads per row (the second wraps to the row's start after column P - 1), a two-table
// permutation (vpermt2ps) per corner. kOneTable (AVX2, SSE4, SSSE3): N columns of one load per
// row, the window clamped into the row, a single-table permutation per corner. kNone: gathers
// only.
enum class FbmWindow { kNone, kOneTable, kTwoTables };

#if RELIEF_FBM_X86 && HWY_TARGET <= HWY_AVX3
inline constexpr FbmWindow kFbmWindow = FbmWindow::kTwoTables;
#elif RELIEF_FBM_X86
inline constexpr FbmWindow kFbmWindow = FbmWindow::kOneTable;
#else
inline constexpr FbmWindow kFbmWindow = FbmWindow::kNone;
#endif

// The lattice as the fBm kernel sees it.
struct FbmLattice {
  const float* values;
  int shift;  // log2 P: row j starts at j << shift
  int mask;   // P - 1
  float period, inv_period;
  bool window;  // windows on this target, and P >= N: a window fits in a row
};

template <class D>
FbmLattice FbmLatticeOf(D d, const NoiseLattice& lattice) {
  int shift = 0;
  while ((1 << shift) < lattice.size) {
    ++shift;
  }
  return {
      lattice.values.data(),
      shift,
      lattice.mask,
      float(lattice.size),
      1.0f / float(lattice.size),
      kFbmWindow != FbmWindow::kNone && static_cast<std::size_t>(lattice.size) >= hn::MaxLanes(d)};
}

// float to int32 by truncation (cvttps2dq): exact for the integers below 2^31 it is given
// here, INT32_MIN for larger ones (which the callers then reject as negative). Highway's
// ConvertTo adds four operations of saturation.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> TruncateToInt(D d, V v) {
  const hn::RebindToSigned<D> di;
  (void)d;
#if RELIEF_FBM_X86 && HWY_TARGET <= HWY_AVX3
  return hn::Vec<decltype(di)>{_mm512_cvttps_epi32(v.raw)};
#elif RELIEF_FBM_X86 && HWY_TARGET == HWY_AVX2
  return hn::Vec<decltype(di)>{_mm256_cvttps_epi32(v.raw)};
#elif RELIEF_FBM_X86
  return hn::Vec<decltype(di)>{_mm_cvttps_epi32(v.raw)};
#else
  return hn::ConvertTo(di, v);
#endif
}

// Whether every lane of v is at most `limit` (unsigned): one comparison on AVX3, a minimum and
// an equality before.
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE bool AllAtMost(DU du, VU v, std::uint32_t limit) {
#if RELIEF_FBM_X86 && HWY_TARGET <= HWY_AVX3
  return hn::AllTrue(du, hn::Lt(v, hn::Set(du, limit + 1)));  // limit < 2^32 - 1
#else
  return hn::AllTrue(du, hn::Eq(hn::Min(v, hn::Set(du, limit)), v));
#endif
}

// The values of lattice row j (masked) at the window's lanes pos0 and pos1: `base` and `upper`
// the columns its (first and second) loads start at.
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE void LookupRow(D d, const FbmLattice& l, int j, int base, int upper, VI pos0, VI pos1,
                          V& at0, V& at1) {
  const float* values = l.values + (static_cast<std::ptrdiff_t>(j) << l.shift);
#if RELIEF_FBM_X86 && HWY_TARGET <= HWY_AVX3
  const V lo = hn::LoadU(d, values + base), hi = hn::LoadU(d, values + upper);
  at0 = V{_mm512_permutex2var_ps(lo.raw, pos0.raw, hi.raw)};
  at1 = V{_mm512_permutex2var_ps(lo.raw, pos1.raw, hi.raw)};
#else
  (void)upper;
  const V lo = hn::LoadU(d, values + base);
  at0 = hn::TableLookupLanes(lo, hn::IndicesFromVec(d, pos0));
  at1 = hn::TableLookupLanes(lo, hn::IndicesFromVec(d, pos1));
#endif
}

// The four corners from windows where the cells fit; false otherwise. `column` and `row`: per
// lane, integers congruent modulo P to floor(wx) and floor(wz) of locate_cell, or negative
// (then false). The lanes lie in one lattice row (windows of rows j0 and j0 + 1) or in two
// neighbouring ones (rows j, j + 1 and j + 2, chosen per lane), and their columns i0 and i0 + 1
// in the window's: then i1 = i0 + 1 modulo P is the window's next lane, wrap included.
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE bool WindowCorners(D d, const FbmLattice& l, VI column, VI row, V& v00, V& v10, V& v01,
                              V& v11) {
  const hn::RebindToSigned<D> di;
  const hn::RebindToUnsigned<D> du;
  constexpr int kLanes = static_cast<int>(hn::MaxLanes(d));
  const int column_first = hn::GetLane(column);
  const int row_first = hn::GetLane(row);
  if (column_first < 0 || row_first < 0) {
    return false;
  }
  // The window starts at column `start` (not masked: start >= 0, so pos0 in range puts every
  // column at or right of it), base = start mod P.
  int start, base, upper, last;  // last: the largest pos0 whose pos0 + 1 is in the window
  if constexpr (kFbmWindow == FbmWindow::kTwoTables) {
    // A multiple of N, N/2 to 3N/2 - 1 columns left of lane 0's (or 0).
    start = (column_first - kLanes / 2) & ~(kLanes - 1);
    start = start < 0 ? 0 : start;
    base = start & l.mask;
    upper = (base + kLanes) & l.mask;
    last = 2 * kLanes - 2;
  } else {
    // N/2 - 1 columns left of lane 0's, within the row.
    const int first = column_first & l.mask;
    base = first - (kLanes / 2 - 1);
    base = base < 0 ? 0 : base > l.mask + 1 - kLanes ? l.mask + 1 - kLanes : base;
    start = column_first - (first - base);
    upper = base;
    last = kLanes - 2;
  }
  const VI pos0 = hn::Sub(column, hn::Set(di, start));
  if (!AllAtMost(du, hn::BitCast(du, pos0), static_cast<std::uint32_t>(last))) {
    return false;  // a column left of the window, or whose neighbour is right of it
  }
  const VI pos1 = hn::Add(pos0, hn::Set(di, 1));
  if (HWY_LIKELY(hn::AllTrue(di, hn::Eq(row, hn::Set(di, row_first))))) {
    const int j0 = row_first & l.mask;
    LookupRow(d, l, j0, base, upper, pos0, pos1, v00, v10);
    LookupRow(d, l, (j0 + 1) & l.mask, base, upper, pos0, pos1, v01, v11);
    return true;
  }
  const int row_least = hn::GetLane(hn::MinOfLanes(di, row));
  const auto above = hn::BitCast(du, hn::Sub(row, hn::Set(di, row_least)));
  if (row_least < 0 || !AllAtMost(du, above, 1u)) {
    return false;  // more than two rows
  }
  const auto upper_row = hn::RebindMask(d, hn::Ne(above, hn::Zero(du)));  // j0 = j + 1
  const int j = row_least & l.mask;
  V a0, a1, b0, b1, c0, c1;  // rows j, j + 1, j + 2 at pos0 and pos1
  LookupRow(d, l, j, base, upper, pos0, pos1, a0, a1);
  LookupRow(d, l, (j + 1) & l.mask, base, upper, pos0, pos1, b0, b1);
  LookupRow(d, l, (j + 2) & l.mask, base, upper, pos0, pos1, c0, c1);
  v00 = hn::IfThenElse(upper_row, b0, a0);
  v10 = hn::IfThenElse(upper_row, b1, a1);
  v01 = hn::IfThenElse(upper_row, c0, b0);
  v11 = hn::IfThenElse(upper_row, c1, b1);
  return true;
}

// The four corners by gathers. `column` and `row`: integers congruent modulo P to floor(wx)
// and floor(wz), not negative. (v00, v10) and (v01, v11) are neighbours in a lattice row
// unless i0 = P - 1, whose pair would read the next row's first value (and past the lattice
// in its last row): where no lane has i0 = P - 1, one 64-bit gather per pair (AVX2, AVX3).
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE void GatherCorners(D d, const FbmLattice& l, VI column, VI row, V& v00, V& v10, V& v01,
                              V& v11) {
  const hn::RebindToSigned<D> di;
  const VI mask = hn::Set(di, l.mask);
  const VI one = hn::Set(di, 1);
  const VI i0 = hn::And(column, mask);
  const VI j0 = hn::And(row, mask);
  const VI j1 = hn::And(hn::Add(j0, one), mask);
  const VI at00 = hn::Add(hn::ShiftLeftSame(j0, l.shift), i0);
  const VI at01 = hn::Add(hn::ShiftLeftSame(j1, l.shift), i0);
#if RELIEF_FBM_X86 && RELIEF_PAIR_GATHER
  if (HWY_LIKELY(hn::AllFalse(di, hn::Eq(i0, mask)))) {
    GatherFloatPairs(l.values, at00, v00, v10);
    GatherFloatPairs(l.values, at01, v01, v11);
    return;
  }
#endif
  const VI step = hn::Sub(hn::And(hn::Add(i0, one), mask), i0);  // i1 - i0: 1, or 1 - P
  v00 = hn::GatherIndex(d, l.values, at00);
  v10 = hn::GatherIndex(d, l.values, hn::Add(at00, step));
  v01 = hn::GatherIndex(d, l.values, at01);
  v11 = hn::GatherIndex(d, l.values, hn::Add(at01, step));
}

// The fractions and corners of SampleFbmLattice where some lane's coordinate is negative (or
// 2^31 or more; every lane on targets without RELIEF_FBM_X86): wrap_period first, as
// SampleLattice. Out of line on x86, where it is the rare case.
#if RELIEF_FBM_X86
#define RELIEF_FBM_WRAPPED HWY_NOINLINE
#else
#define RELIEF_FBM_WRAPPED HWY_INLINE
#endif
template <class D, class V = hn::Vec<D>>
RELIEF_FBM_WRAPPED void SampleWrapped(D d, const FbmLattice& l, V px, V pz, V& fraction_x,
                                      V& fraction_z, V& v00, V& v10, V& v01, V& v11) {
  const V period = hn::Set(d, l.period);
  const V inv_period = hn::Set(d, l.inv_period);
  const V wx = WrapPeriod(d, px, period, inv_period);
  const V wz = WrapPeriod(d, pz, period, inv_period);
  const V fx = hn::Floor(wx);
  const V fz = hn::Floor(wz);
  const auto column = TruncateToInt(d, fx);  // fx in [0, P]: exact
  const auto row = TruncateToInt(d, fz);
  fraction_x = hn::Sub(wx, fx);
  fraction_z = hn::Sub(wz, fz);
  if (!(l.window && WindowCorners(d, l, column, row, v00, v10, v01, v11))) {
    GatherCorners(d, l, column, row, v00, v10, v01, v11);
  }
}

// sample_lattice<kKind> at (px, pz), bit for bit SampleLattice.
//
// For p >= 0, wrap_period subtracts P k with k = floor(p / P), exactly (interpolant.h): so
// floor(wx) = floor(p) - P k (the same column modulo P) and wx - floor(wx) has the exact value
// p - floor(p), the same float. (-0 too: floor(-0) = -0 truncates to column 0 and -0 - -0 is
// +0, as wrap_period makes it.) Truncation gives a negative column for p < 0 and INT32_MIN for
// p >= 2^31: then wrap_period first, as SampleLattice.
template <Interpolant kKind, class D, class V = hn::Vec<D>>
HWY_INLINE V SampleFbmLattice(D d, const FbmLattice& l, V px, V pz) {
  V fraction_x, fraction_z;
  V v00, v10, v01, v11;
#if RELIEF_FBM_X86
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V floor_x = hn::Floor(px);
  const V floor_z = hn::Floor(pz);
  const VI column = TruncateToInt(d, floor_x);
  const VI row = TruncateToInt(d, floor_z);
  // WindowCorners accepts no negative column or row.
  const bool windowed = l.window && WindowCorners(d, l, column, row, v00, v10, v01, v11);
  if (windowed || HWY_LIKELY(hn::AllFalse(di, hn::Lt(hn::Or(column, row), hn::Zero(di))))) {
    fraction_x = hn::Sub(px, floor_x);
    fraction_z = hn::Sub(pz, floor_z);
    if (!windowed) {
      GatherCorners(d, l, column, row, v00, v10, v01, v11);
    }
  } else
#endif
  {
    SampleWrapped(d, l, px, pz, fraction_x, fraction_z, v00, v10, v01, v11);
  }
  const V tx = Fade<kKind>(d, fraction_x);
  const V tz = Fade<kKind>(d, fraction_z);
  const V bottom = hn::Add(v00, hn::Mul(tx, hn::Sub(v10, v00)));
  const V top = hn::Add(v01, hn::Mul(tx, hn::Sub(v11, v01)));
  return hn::Add(bottom, hn::Mul(tz, hn::Sub(top, bottom)));
}

#undef RELIEF_FBM_WRAPPED
#undef RELIEF_FBM_X86

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
