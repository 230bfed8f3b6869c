// Per-target 64-bit pair gathers: for each lane k, the two consecutive floats at base + at[k],
// as two vectors. One 64-bit gather per half vector and two lane permutations instead of two
// 32-bit gathers: half the gathered elements, and on the AMD cores a gather costs about one
// load per element. Used where neighbouring values (a lattice cell's two corners of a row, a
// texel's channels and its right neighbour's) lie next to each other in memory. Only where the
// values come from changes, never how they are combined, so results are bit-identical to the
// 32-bit gathers they replace.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_PAIR_GATHER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PAIR_GATHER_INL_H_
#undef RELIEF_SIMD_PAIR_GATHER_INL_H_
#else
#define RELIEF_SIMD_PAIR_GATHER_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

// AVX2 and AVX3 have the 64-bit gathers with 32-bit indices; elsewhere callers gather floats.
// Defined anew for each target this header is compiled for.
#undef RELIEF_PAIR_GATHER
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define RELIEF_PAIR_GATHER 1

// Per lane k: first[k] = base[at[k]], second[k] = base[at[k] + 1]. `at` holds float indices
// (the gather's scale is 4 bytes), so a pair may start at any float.
template <class V, class VI>
HWY_INLINE void GatherFloatPairs(const float* base, VI at, V& first, V& second) {
  const auto* pairs = reinterpret_cast<const long long*>(base);  // NOLINT(runtime/int)
#if HWY_TARGET <= HWY_AVX3
  const __m512 lo =
      _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_castsi512_si256(at.raw), pairs, 4));
  const __m512 hi =
      _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_extracti64x4_epi64(at.raw, 1), pairs, 4));
  const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  const __m512i odd = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
  first = V{_mm512_permutex2var_ps(lo, even, hi)};
  second = V{_mm512_permutex2var_ps(lo, odd, hi)};
#else
  const __m256 lo =
      _mm256_castsi256_ps(_mm256_i32gather_epi64(pairs, _mm256_castsi256_si128(at.raw), 4));
  const __m256 hi =
      _mm256_castsi256_ps(_mm256_i32gather_epi64(pairs, _mm256_extracti128_si256(at.raw, 1), 4));
  // shuffle_ps: (lo0 lo2 hi0 hi2 | lo4 lo6 hi4 hi6) for the first floats of the pairs; its
  // 64-bit quarters in the order 0 2 1 3 are lanes 0 .. 7.
  first = V{_mm256_castpd_ps(_mm256_permute4x64_pd(
      _mm256_castps_pd(_mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0))), 0xD8))};
  second = V{_mm256_castpd_ps(_mm256_permute4x64_pd(
      _mm256_castps_pd(_mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1))), 0xD8))};
#endif
}
#else
#define RELIEF_PAIR_GATHER 0
#endif

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
