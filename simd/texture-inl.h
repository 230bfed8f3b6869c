// Per-target proto-texture sampling of core/proto_texture.cc for float, one sample per lane:
// texture_lod (GL's isotropic LOD from log2_det) and sample_trilinear (GL_REPEAT,
// GL_LINEAR_MIPMAP_LINEAR) with the scalar code's operations in its order. The mip chain is
// one array (ProtoTexture::texels), so each lane addresses its own level: a level's side, its
// reciprocal, its row shift and its start in the chain are integer functions of the level
// (sides are powers of two), and every lane reads exactly the one or two levels its sample
// blends, whatever the spread of levels across the vector. Texels are gathered per channel
// (hn::GatherIndex, int32 indices) or, on AVX2 and AVX3, a texel and its right neighbour
// loaded per lane and transposed (simd/lane_loads-inl.h). Each lane sees exactly the scalar
// arithmetic for its sample; the indices of inactive lanes are in range too (level 0,
// coordinates wrapped and masked like the scalar code's), so no gather reads outside the chain.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_TEXTURE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_TEXTURE_INL_H_
#undef RELIEF_SIMD_TEXTURE_INL_H_
#else
#define RELIEF_SIMD_TEXTURE_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "core/proto_texture.h"
#include "simd/det_math-inl.h"
#include "simd/lane_loads-inl.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// A proto-texture's mip chain as the kernel reads it: level k has side size0 >> k and starts
// at float 4 (size0^2 - side^2) of `texels` (core/proto_texture.h).
struct TextureView {
  const float* texels = nullptr;
  int shift0 = 0;   // log2 of level 0's side
  int last = 0;     // levels - 1 (= shift0)
  float size0 = 0;  // float(level 0's side), texture_lod's n
};

inline TextureView texture_view_of(const ProtoTexture& t) {
  TextureView v;
  v.texels = t.texels.data();
  v.last = static_cast<int>(t.levels.size()) - 1;
  while ((1 << v.shift0) < t.levels[0].size) {
    ++v.shift0;
  }
  v.size0 = float(t.levels[0].size);
  return v;
}

// texture_lod: 0.5 log2_det(max(|(du/dx, dv/dx)|^2, |(du/dy, dv/dy)|^2)) in level-0 texels,
// kMagnificationLod where rho^2 is not above 1e-30 (or NaN).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V TextureLod(D d, float size0, V dudx, V dvdx, V dudy, V dvdy) {
  const V n = hn::Set(d, size0);
  const V ax = hn::Mul(dudx, n), bx = hn::Mul(dvdx, n);
  const V ay = hn::Mul(dudy, n), by = hn::Mul(dvdy, n);
  const V rho_sq =
      StdMax(hn::Add(hn::Mul(ax, ax), hn::Mul(bx, bx)), hn::Add(hn::Mul(ay, ay), hn::Mul(by, by)));
  const auto defined = hn::Gt(rho_sq, hn::Set(d, 1e-30f));
  return hn::IfThenElse(defined, hn::Mul(hn::Set(d, 0.5f), Log2Det(d, rho_sq)),
                        hn::Set(d, kMagnificationLod));
}

// wrap (proto_texture.cc): x - n trunc(x / n), 0 where x is not finite. x / n is computed as
// x * (1 / n): n is a power of two, so 1 / n is exact and both are the correctly rounded value
// of the same real number x 2^-k, bit for bit (subnormal results included).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V WrapTexture(D /*d*/, V x, V n, V inv_n) {
  return hn::IfThenElseZero(hn::IsFinite(x), hn::Sub(x, hn::Mul(n, hn::Trunc(hn::Mul(x, inv_n)))));
}

// sample_bilinear for every lane at its own level (0 .. last): side n = size0 >> level.
template <class D, class V = hn::Vec<D>, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE V3<V> SampleBilinear(D d, const TextureView& t, VI level, V u, V v) {
  const hn::RebindToSigned<D> di;
  const VI side_shift = hn::Sub(hn::Set(di, t.shift0), level);  // log2 n
  const VI one = hn::Set(di, 1);
  const VI side = hn::Set(di, 1) << side_shift;
  const V n = hn::ConvertTo(d, side);
  // 1 / n = 2^-log2(n), built in the exponent field: exact, as float(1) / float(n) is.
  const V inv_n = hn::BitCast(d, hn::ShiftLeft<23>(hn::Sub(hn::Set(di, 127), side_shift)));
  const V half = hn::Set(d, 0.5f);
  const V s = WrapTexture(d, hn::Sub(hn::Mul(u, n), half), n, inv_n);
  const V tt = WrapTexture(d, hn::Sub(hn::Mul(v, n), half), n, inv_n);
  const V fs = hn::Floor(s), ft = hn::Floor(tt);
  const V a = hn::Sub(s, fs), b = hn::Sub(tt, ft);
  const VI mask = hn::Sub(side, one);
  // -n <= fs, ft < n after the wrap: the conversion is exact and the mask wraps negatives.
  const VI i0 = hn::And(hn::ConvertTo(di, fs), mask);
  const VI j0 = hn::And(hn::ConvertTo(di, ft), mask);
  const VI i1 = hn::And(hn::Add(i0, one), mask);
  const VI j1 = hn::And(hn::Add(j0, one), mask);
  // The level's start in the chain, 4 (size0^2 - n^2), plus 3 (j n + i): the texel's red.
  const VI start =
      hn::Sub(hn::Set(di, 4 << (2 * t.shift0)), hn::Set(di, 4) << hn::Add(side_shift, side_shift));
  const auto times3 = [](VI x) { return hn::Add(hn::ShiftLeft<1>(x), x); };
  const VI row0 = hn::Add(start, times3(j0 << side_shift));
  const VI row1 = hn::Add(start, times3(j1 << side_shift));
  const VI k00 = hn::Add(row0, times3(i0));
  const VI k10 = hn::Add(row0, times3(i1));
  const VI k01 = hn::Add(row1, times3(i0));
  const VI k11 = hn::Add(row1, times3(i1));
  const float* base = t.texels;
  V p00[3], p10[3], p01[3], p11[3];
#if RELIEF_LANE_LOADS
  // Texels (i0, j) and (i1, j) are the six floats r g b r g b from 3 (j n + i0) unless i0 is
  // the last column: then one load per lane and row, transposed (lane_loads-inl.h), else one
  // per texel. Each load reads up to eight floats: the chain is padded (ProtoTexture).
  V row[6];
  if (HWY_LIKELY(hn::AllFalse(di, hn::Eq(i0, mask)))) {
    LoadTexelRows(base, k00, row);
    for (int c = 0; c < 3; ++c) {
      p00[c] = row[c];
      p10[c] = row[3 + c];
    }
    LoadTexelRows(base, k01, row);
    for (int c = 0; c < 3; ++c) {
      p01[c] = row[c];
      p11[c] = row[3 + c];
    }
  } else {
    const auto load_texel = [&](VI at, V(&texel)[3]) {
      LoadTexelRows(base, at, row);
      for (int c = 0; c < 3; ++c) {
        texel[c] = row[c];
      }
    };
    load_texel(k00, p00);
    load_texel(k10, p10);
    load_texel(k01, p01);
    load_texel(k11, p11);
  }
#else
  for (int c = 0; c < 3; ++c) {
    p00[c] = hn::GatherIndex(d, base + c, k00);
    p10[c] = hn::GatherIndex(d, base + c, k10);
    p01[c] = hn::GatherIndex(d, base + c, k01);
    p11[c] = hn::GatherIndex(d, base + c, k11);
  }
#endif
  V out[3];
  for (int c = 0; c < 3; ++c) {
    const V bottom = hn::Add(p00[c], hn::Mul(a, hn::Sub(p10[c], p00[c])));
    const V top = hn::Add(p01[c], hn::Mul(a, hn::Sub(p11[c], p01[c])));
    out[c] = hn::Add(bottom, hn::Mul(b, hn::Sub(top, bottom)));
  }
  return {out[0], out[1], out[2]};
}

// sample_trilinear for the lanes of `active` (the others' results are unspecified): level 0
// where lod <= 0 (or NaN), the last level where lod >= last, else the two levels around lod
// blended by its fraction (a whole lod: its level alone).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> SampleTrilinear(D d, const TextureView& t, V u, V v, V lod, M active) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d);
  const V last_f = hn::Set(d, float(t.last));
  const M magnify = hn::Not(hn::Gt(lod, zero));
  const M minify_most = hn::AndNot(magnify, hn::Ge(lod, last_f));
  const M trilinear = hn::AndNot(hn::Or(magnify, minify_most), active);
  // int(lod) only matters where 0 < lod < last; elsewhere it is replaced.
  const auto truncated = hn::ConvertTo(di, hn::IfThenElseZero(trilinear, lod));
  const V fraction = hn::Sub(lod, hn::ConvertTo(d, truncated));
  // A whole lod reads its level alone, as sample_trilinear returns it.
  const M blend = hn::And(trilinear, hn::Ne(fraction, zero));
  auto level = hn::IfThenElse(hn::RebindMask(di, minify_most), hn::Set(di, t.last), truncated);
  level = hn::IfThenZeroElse(hn::RebindMask(di, magnify), level);
  const V3<V> first_sample = SampleBilinear(d, t, level, u, v);
  V3<V> second_sample = first_sample;
  if (!hn::AllFalse(d, blend)) {
    const auto next = hn::Add(level, hn::IfThenElseZero(hn::RebindMask(di, blend), hn::Set(di, 1)));
    second_sample = SampleBilinear(d, t, next, u, v);
  }
  const V3<V> blended = {
      hn::Add(first_sample.x, hn::Mul(fraction, hn::Sub(second_sample.x, first_sample.x))),
      hn::Add(first_sample.y, hn::Mul(fraction, hn::Sub(second_sample.y, first_sample.y))),
      hn::Add(first_sample.z, hn::Mul(fraction, hn::Sub(second_sample.z, first_sample.z)))};
  return Select3(blend, blended, first_sample);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
