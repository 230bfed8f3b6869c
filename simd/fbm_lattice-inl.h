// Per-target lattice sampling for the fBm kernel (simd/fbm-inl.h): sample_lattice<kKind> of
// core/interpolant.h on a vector of points, with the same floating-point operations in the
// same order per lane as SampleLattice (simd/lattice-inl.h), but fetching the four corner
// values without gathers where the vector's points are close together (a grid row, an
// octave's cells larger than the points' spacing): every lane in one lattice row and within a
// window of 2N consecutive columns (N lanes), the window is two aligned vector loads per row
// and the corners are lane permutations of it. Elsewhere the four gathers of SampleLattice.
// Only where the values come from differs: the results are bit for bit those of
// SampleLattice.
#if defined(RELIEF_SIMD_FBM_LATTICE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_FBM_LATTICE_INL_H_
#undef RELIEF_SIMD_FBM_LATTICE_INL_H_
#else
#define RELIEF_SIMD_FBM_LATTICE_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "core/interpolant.h"
#include "simd/lattice-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

// The targets whose permutations make the window cheaper than gathers.
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
inline constexpr bool kFbmWindow = true;
#else
inline constexpr bool kFbmWindow = false;
#endif

// Lane k of the 2N-lane table (lo, hi) at index pos[k] in [0, 2N).
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE V LookupWindow(D d, V lo, V hi, VI pos) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  (void)d;
  return V{_mm512_permutex2var_ps(lo.raw, pos.raw, hi.raw)};
#elif HWY_ARCH_X86 && HWY_TARGET == HWY_AVX2
  (void)d;
  // vpermps reads the low three bits of each index; bit 3 chooses the half.
  const __m256 from_lo = _mm256_permutevar8x32_ps(lo.raw, pos.raw);
  const __m256 from_hi = _mm256_permutevar8x32_ps(hi.raw, pos.raw);
  return V{_mm256_blendv_ps(from_lo, from_hi, _mm256_castsi256_ps(_mm256_slli_epi32(pos.raw, 28)))};
#else
  const hn::RebindToSigned<D> di;
  const VI half = hn::Set(di, static_cast<std::int32_t>(hn::Lanes(d)));
  const VI low = hn::IfThenElse(hn::Lt(pos, half), pos, hn::Sub(pos, half));
  const auto idx = hn::IndicesFromVec(d, low);
  return hn::IfThenElse(hn::RebindMask(d, hn::Lt(pos, half)), hn::TableLookupLanes(lo, idx),
                        hn::TableLookupLanes(hi, idx));
#endif
}

// sample_lattice<kKind> at (px, pz), as SampleLattice.
template <Interpolant kKind, class D, class V = hn::Vec<D>>
HWY_INLINE V SampleLatticeWindowed(D d, const LatticeView& l, V period, V inv_period, V px, V pz) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V wx = WrapPeriod(d, px, period, inv_period);
  const V wz = WrapPeriod(d, pz, period, inv_period);
  const V fx = hn::Floor(wx);
  const V fz = hn::Floor(wz);
  const VI mask = hn::Set(di, l.mask);
  const VI i0 = hn::And(hn::ConvertTo(di, fx), mask);  // fx in [0, P]: exact
  const V tx = Fade<kKind>(d, hn::Sub(wx, fx));
  const V tz = Fade<kKind>(d, hn::Sub(wz, fz));
  V v00, v10, v01, v11;
  bool fetched = false;
  if constexpr (kFbmWindow) {
    constexpr int kLanes = static_cast<int>(hn::MaxLanes(d));
    const float fz_first = hn::GetLane(fz);
    if (l.mask >= kLanes - 1 && hn::AllTrue(d, hn::Eq(fz, hn::Set(d, fz_first)))) {
      // One lattice row j0 (and j1) for every lane. The window: columns base .. base + 2N - 1
      // (mod P), base a multiple of N within N/2 .. 3N/2 - 1 columns left of lane 0's i0.
      const int i_first = hn::GetLane(i0);
      const int base = ((i_first - kLanes / 2) & l.mask) & ~(kLanes - 1);
      const VI pos0 = hn::And(hn::Sub(i0, hn::Set(di, base)), mask);
      if (hn::AllTrue(di, hn::Lt(pos0, hn::Set(di, 2 * kLanes - 1)))) {
        const int j0 = static_cast<int>(fz_first) & l.mask;
        const int j1 = (j0 + 1) & l.mask;
        const int upper = (base + kLanes) & l.mask;
        const float* row0 = l.values + (static_cast<std::ptrdiff_t>(j0) << l.shift);
        const float* row1 = l.values + (static_cast<std::ptrdiff_t>(j1) << l.shift);
        const V lo0 = hn::LoadU(d, row0 + base), hi0 = hn::LoadU(d, row0 + upper);
        const V lo1 = hn::LoadU(d, row1 + base), hi1 = hn::LoadU(d, row1 + upper);
        const VI pos1 = hn::Add(pos0, hn::Set(di, 1));
        v00 = LookupWindow(d, lo0, hi0, pos0);
        v10 = LookupWindow(d, lo0, hi0, pos1);
        v01 = LookupWindow(d, lo1, hi1, pos0);
        v11 = LookupWindow(d, lo1, hi1, pos1);
        fetched = true;
      }
    }
  }
  if (!fetched) {
    const VI one = hn::Set(di, 1);
    const VI j0 = hn::And(hn::ConvertTo(di, fz), mask);
    const VI i1 = hn::And(hn::Add(i0, one), mask);
    const VI j1 = hn::And(hn::Add(j0, one), mask);
    const VI row0 = hn::ShiftLeftSame(j0, l.shift);
    const VI row1 = hn::ShiftLeftSame(j1, l.shift);
    v00 = hn::GatherIndex(d, l.values, hn::Add(row0, i0));
    v10 = hn::GatherIndex(d, l.values, hn::Add(row0, i1));
    v01 = hn::GatherIndex(d, l.values, hn::Add(row1, i0));
    v11 = hn::GatherIndex(d, l.values, hn::Add(row1, i1));
  }
  const V bottom = hn::Add(v00, hn::Mul(tx, hn::Sub(v10, v00)));
  const V top = hn::Add(v01, hn::Mul(tx, hn::Sub(v11, v01)));
  return hn::Add(bottom, hn::Mul(tz, hn::Sub(top, bottom)));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
