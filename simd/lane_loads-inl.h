// Per-target loads of consecutive floats per lane, transposed into one vector per column: for
// each lane k, out[c][k] = base[at[k] + c]. On the AMD cores a gather costs about two cycles
// per element, while unaligned 256-bit loads issue at up to three a cycle and an 8 x 8
// transpose is 24 shuffles: one load per lane and a transpose replace up to eight gathers.
// Used for a bilinear footprint's row, two neighbouring RGB texels (six consecutive floats,
// simd/texture-inl.h), and for a resolve slot's record of vertex values (simd/resolve-inl.h).
// Only where the values come from changes, so results are bit-identical to gathering them.
// Each lane's load reads eight floats, base[at[k]] to base[at[k] + 7]: callers keep them
// readable.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_LANE_LOADS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_LANE_LOADS_INL_H_
#undef RELIEF_SIMD_LANE_LOADS_INL_H_
#else
#define RELIEF_SIMD_LANE_LOADS_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// AVX2 and AVX3 transpose with raw shuffles; elsewhere callers gather.
#undef RELIEF_LANE_LOADS
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define RELIEF_LANE_LOADS 1

// The 8 x 8 transpose of the rows r[0 .. 7] within 128-bit blocks (unpack, then shuffle):
// u[c] holds column c of rows 0-3 in each even block and column c + 4 in each odd one, u[4 + c]
// the same of rows 4-7; the caller combines the blocks. Works on 256-bit and 512-bit
// registers alike (the shuffles act per 128-bit block).
template <class R>
HWY_INLINE void TransposeBlocks(const R (&r)[8], R (&u)[8]) {
  R t[8];
  for (int p = 0; p < 4; ++p) {
    if constexpr (sizeof(R) == 64) {
      t[2 * p] = _mm512_unpacklo_ps(r[2 * p], r[2 * p + 1]);
      t[2 * p + 1] = _mm512_unpackhi_ps(r[2 * p], r[2 * p + 1]);
    } else {
      t[2 * p] = _mm256_unpacklo_ps(r[2 * p], r[2 * p + 1]);
      t[2 * p + 1] = _mm256_unpackhi_ps(r[2 * p], r[2 * p + 1]);
    }
  }
  // u[4 h + c] for rows 4h .. 4h + 3: columns c (c = 0 .. 3) in the low half of each 128-bit
  // block pair's first block, columns c + 4 in the second.
  for (int h = 0; h < 2; ++h) {
    const R& a = t[4 * h];
    const R& b = t[4 * h + 1];
    const R& c = t[4 * h + 2];
    const R& d = t[4 * h + 3];
    if constexpr (sizeof(R) == 64) {
      u[4 * h + 0] = _mm512_shuffle_ps(a, c, 0x44);
      u[4 * h + 1] = _mm512_shuffle_ps(a, c, 0xEE);
      u[4 * h + 2] = _mm512_shuffle_ps(b, d, 0x44);
      u[4 * h + 3] = _mm512_shuffle_ps(b, d, 0xEE);
    } else {
      u[4 * h + 0] = _mm256_shuffle_ps(a, c, 0x44);
      u[4 * h + 1] = _mm256_shuffle_ps(a, c, 0xEE);
      u[4 * h + 2] = _mm256_shuffle_ps(b, d, 0x44);
      u[4 * h + 3] = _mm256_shuffle_ps(b, d, 0xEE);
    }
  }
}

template <class V, class VI>
HWY_INLINE void LoadTexelRows(const float* base, VI at, V (&out)[6]) {
#if HWY_TARGET <= HWY_AVX3
  // Lanes l and l + 8 share register l: the low 256 bits hold lane l's eight floats.
  alignas(64) std::int32_t index[16];
  _mm512_store_si512(index, at.raw);
  __m512 r[8], u[8];
  for (int l = 0; l < 8; ++l) {
    r[l] = _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_loadu_ps(base + index[l])),
                              _mm256_loadu_ps(base + index[l + 8]), 1);
  }
  TransposeBlocks(r, u);
  // u[c] (rows 0-3) and u[4 + c] (rows 4-7) hold column c in 128-bit blocks 0 (lanes 0-3,
  // 4-7 of the next) and 2 (lanes 8-11, 12-15); column c + 4 in blocks 1 and 3.
  const __m512i low = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27);
  const __m512i high =
      _mm512_setr_epi32(4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31);
  for (int c = 0; c < 4; ++c) {
    out[c] = V{_mm512_permutex2var_ps(u[c], low, u[4 + c])};
  }
  for (int c = 0; c < 2; ++c) {
    out[4 + c] = V{_mm512_permutex2var_ps(u[c], high, u[4 + c])};
  }
#else
  alignas(32) std::int32_t index[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(index), at.raw);
  __m256 r[8], u[8];
  for (int l = 0; l < 8; ++l) {
    r[l] = _mm256_loadu_ps(base + index[l]);
  }
  TransposeBlocks(r, u);
  for (int c = 0; c < 4; ++c) {
    out[c] = V{_mm256_permute2f128_ps(u[c], u[4 + c], 0x20)};
  }
  for (int c = 0; c < 2; ++c) {
    out[4 + c] = V{_mm256_permute2f128_ps(u[c], u[4 + c], 0x31)};
  }
#endif
}

// Eight columns of eight floats per lane, for the float half of double-lane kernels: 8 lanes
// (a 256-bit vector, AVX3) or 4 lanes (a 128-bit vector, AVX2). `index` holds the lanes'
// float offsets from base.
template <class VF>
HWY_INLINE void LoadColumns8(const float* base, const std::int32_t* index, VF (&out)[8]) {
  if constexpr (sizeof(out[0].raw) == 32) {
    __m256 r[8], u[8];
    for (int l = 0; l < 8; ++l) {
      r[l] = _mm256_loadu_ps(base + index[l]);
    }
    TransposeBlocks(r, u);
    for (int c = 0; c < 4; ++c) {
      out[c] = VF{_mm256_permute2f128_ps(u[c], u[4 + c], 0x20)};
      out[4 + c] = VF{_mm256_permute2f128_ps(u[c], u[4 + c], 0x31)};
    }
  } else {
    // Four rows: unpack and shuffle leave column c in the low 128 bits of u[c] and column
    // c + 4 in its high 128 bits.
    __m256 r[4];
    for (int l = 0; l < 4; ++l) {
      r[l] = _mm256_loadu_ps(base + index[l]);
    }
    const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
    const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
    const __m256 u[4] = {_mm256_shuffle_ps(t0, t2, 0x44), _mm256_shuffle_ps(t0, t2, 0xEE),
                         _mm256_shuffle_ps(t1, t3, 0x44), _mm256_shuffle_ps(t1, t3, 0xEE)};
    for (int c = 0; c < 4; ++c) {
      out[c] = VF{_mm256_castps256_ps128(u[c])};
      out[4 + c] = VF{_mm256_extractf128_ps(u[c], 1)};
    }
  }
}
#else
#define RELIEF_LANE_LOADS 0
#endif

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
