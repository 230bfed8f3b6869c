// Per-target proto-texture sampling of core/proto_texture.cc for float, one sample per lane:
// texture_lod (GL's isotropic LOD from log2_det) and sample_trilinear (GL_REPEAT,
// GL_LINEAR_MIPMAP_LINEAR) with the scalar code's operations in its order. Texels are gathered
// per channel (hn::GatherIndex, int32 indices) from the level each lane reads: the levels are
// separate arrays, so the vector walks the levels its lanes need (usually two or three
// neighbours), computes every lane's coordinates at that level's size, gathers, and keeps the
// lanes that read that level. Each lane thus sees exactly the scalar arithmetic for its sample;
// the indices of the other lanes are in range too (wrapped and masked like the scalar code's),
// so no gather reads outside a level.
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
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// A proto-texture's mip chain as the kernel reads it.
struct TextureView {
  static constexpr int kMaxLevels = 32;  // sides up to 2^31
  const float* rgb[kMaxLevels];
  int size[kMaxLevels];
  int shift[kMaxLevels];  // log2 size: row j starts at texel j << shift
  int last = 0;           // levels - 1
  float size0 = 0;        // float(level 0's side), texture_lod's n
};

inline TextureView texture_view_of(const ProtoTexture& t) {
  TextureView v;
  const int levels = static_cast<int>(t.levels.size());
  v.last = levels - 1;
  for (int k = 0; k < levels && k < TextureView::kMaxLevels; ++k) {
    v.rgb[k] = t.levels[k].rgb.data();
    v.size[k] = t.levels[k].size;
    int shift = 0;
    while ((1 << shift) < v.size[k]) {
      ++shift;
    }
    v.shift[k] = shift;
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

// sample_bilinear at one level for every lane.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> SampleBilinear(D d, const TextureView& t, int level, V u, V v) {
  const hn::RebindToSigned<D> di;
  const int size = t.size[level];
  const V n = hn::Set(d, float(size));
  const V inv_n = hn::Set(d, 1.0f / float(size));
  const V half = hn::Set(d, 0.5f);
  const V s = WrapTexture(d, hn::Sub(hn::Mul(u, n), half), n, inv_n);
  const V tt = WrapTexture(d, hn::Sub(hn::Mul(v, n), half), n, inv_n);
  const V fs = hn::Floor(s), ft = hn::Floor(tt);
  const V a = hn::Sub(s, fs), b = hn::Sub(tt, ft);
  const auto mask = hn::Set(di, size - 1);
  const auto one = hn::Set(di, 1);
  // -n <= fs, ft < n after the wrap: the conversion is exact and the mask wraps negatives.
  const auto i0 = hn::And(hn::ConvertTo(di, fs), mask);
  const auto j0 = hn::And(hn::ConvertTo(di, ft), mask);
  const auto i1 = hn::And(hn::Add(i0, one), mask);
  const auto j1 = hn::And(hn::Add(j0, one), mask);
  const int shift = t.shift[level];
  const auto row0 = hn::ShiftLeftSame(j0, shift);
  const auto row1 = hn::ShiftLeftSame(j1, shift);
  // 3 (j n + i): the first channel of the texel.
  const auto times3 = [](auto x) { return hn::Add(hn::ShiftLeft<1>(x), x); };
  const auto k00 = times3(hn::Add(row0, i0));
  const auto k10 = times3(hn::Add(row0, i1));
  const auto k01 = times3(hn::Add(row1, i0));
  const auto k11 = times3(hn::Add(row1, i1));
  const float* base = t.rgb[level];
  V out[3];
  for (int c = 0; c < 3; ++c) {
    const V p00 = hn::GatherIndex(d, base + c, k00);
    const V p10 = hn::GatherIndex(d, base + c, k10);
    const V p01 = hn::GatherIndex(d, base + c, k01);
    const V p11 = hn::GatherIndex(d, base + c, k11);
    const V bottom = hn::Add(p00, hn::Mul(a, hn::Sub(p10, p00)));
    const V top = hn::Add(p01, hn::Mul(a, hn::Sub(p11, p01)));
    out[c] = hn::Add(bottom, hn::Mul(b, hn::Sub(top, bottom)));
  }
  return {out[0], out[1], out[2]};
}

// sample_trilinear for the lanes of `active` (the others' results are unspecified): level 0
// where lod <= 0 (or NaN), the last level where lod >= last, else the two levels around lod
// blended by its fraction.
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
  auto level = hn::IfThenElse(hn::RebindMask(di, minify_most), hn::Set(di, t.last), truncated);
  level = hn::IfThenZeroElse(hn::RebindMask(di, magnify), level);
  const auto di_active = hn::RebindMask(di, active);
  const auto di_trilinear = hn::RebindMask(di, trilinear);
  const auto second = hn::Add(level, hn::IfThenElseZero(di_trilinear, hn::Set(di, 1)));
  // The levels the active lanes read: [lowest first level, highest second level].
  const int lowest =
      hn::GetLane(hn::MinOfLanes(di, hn::IfThenElse(di_active, level, hn::Set(di, t.last))));
  const int highest =
      hn::GetLane(hn::MaxOfLanes(di, hn::IfThenElse(di_active, second, hn::Set(di, 0))));
  V3<V> first_sample{zero, zero, zero}, second_sample{zero, zero, zero};
  for (int k = lowest; k <= highest; ++k) {
    const auto kv = hn::Set(di, k);
    const M as_first = hn::And(active, hn::RebindMask(d, hn::Eq(level, kv)));
    const M as_second =
        hn::And(trilinear, hn::RebindMask(d, hn::Eq(hn::Add(level, hn::Set(di, 1)), kv)));
    if (hn::AllFalse(d, hn::Or(as_first, as_second))) {
      continue;
    }
    const V3<V> c = SampleBilinear(d, t, k, u, v);
    first_sample = Select3(as_first, c, first_sample);
    second_sample = Select3(as_second, c, second_sample);
  }
  const V3<V> blended = {
      hn::Add(first_sample.x, hn::Mul(fraction, hn::Sub(second_sample.x, first_sample.x))),
      hn::Add(first_sample.y, hn::Mul(fraction, hn::Sub(second_sample.y, first_sample.y))),
      hn::Add(first_sample.z, hn::Mul(fraction, hn::Sub(second_sample.z, first_sample.z)))};
  return Select3(trilinear, blended, first_sample);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
