// Per-target body of simd/sun_share.h: sun_visibility<float> (core/sun_visibility.cc) on a
// vector of pixels of one row. Each lane does the scalar code's operations for its pixel in
// the scalar code's order; its branches become masks (both sides computed, the scalar's side
// selected: the discarded side's values, even NaN, never reach a lane), its table reads
// gathers; lanes not covered are zeroed first and gather index 0. The scalar lerp, a + (b - a) f,
// is shade_vec3-inl.h's Mix, a + f (b - a): a product rounds alike in either order.
#if defined(RELIEF_SIMD_SUN_SHARE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SUN_SHARE_INL_H_
#undef RELIEF_SIMD_SUN_SHARE_INL_H_
#else
#define RELIEF_SIMD_SUN_SHARE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/sun_horizons.h"
#include "core/sun_visibility.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// disc_share (sun_visibility.cc).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V DiscShare(D d, const ShadowParams<float>& p, V tangent) {
  const V one = hn::Set(d, 1.0f);
  // std::clamp(tangent, -1e6, 1e6).
  const V low = hn::Set(d, -1e6f), high = hn::Set(d, 1e6f);
  const V t = hn::IfThenElse(hn::Lt(tangent, low), low,
                             hn::IfThenElse(hn::Lt(high, tangent), high, tangent));
  const V sine =
      hn::Div(hn::Sub(hn::Set(d, p.sin_elevation), hn::Mul(t, hn::Set(d, p.cos_elevation))),
              hn::Sqrt(hn::Add(one, hn::Mul(t, t))));
  const V ratio = hn::Div(sine, hn::Set(d, p.sin_radius));
  // std::clamp(ratio, -1, 1): ratio < -1 ? -1 : (1 < ratio ? 1 : ratio).
  const V minus_one = hn::Set(d, -1.0f);
  const V x = hn::IfThenElse(hn::Lt(ratio, minus_one), minus_one,
                             hn::IfThenElse(hn::Lt(one, ratio), one, ratio));
  const V half = hn::Set(d, 0.5f);
  const V s = hn::Add(half, hn::Mul(half, x));
  const V smooth = hn::Mul(hn::Mul(s, s), hn::Sub(hn::Set(d, 3.0f), hn::Mul(hn::Set(d, 2.0f), s)));
  return hn::IfThenElse(
      hn::Le(tangent, hn::Set(d, p.lit_tangent)), one,
      hn::IfThenElse(hn::Ge(tangent, hn::Set(d, p.dark_tangent)), hn::Zero(d), smooth));
}

// level_share (sun_visibility.cc) for the lanes of `active`, each at its own level; `proven`
// gets the lanes four comparisons settled.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE V LevelShare(D d, const ShadowParams<float>& p, const SunHorizonCache<float>& c,
                        VI level, V fi, V fj, V height, M active, M& proven) {
  const hn::RebindToSigned<D> di;
  const VI i = hn::ConvertTo(di, fi);  // truncation: both >= 0
  const VI j = hn::ConvertTo(di, fj);
  const V f = hn::Sub(fi, hn::ConvertTo(d, i));
  const V g = hn::Sub(fj, hn::ConvertTo(d, j));
  const VI n = hn::Set(di, c.resolution);
  VI at =
      hn::Add(hn::Mul(hn::Add(hn::Mul(hn::Sub(level, hn::Set(di, c.first_level)), n), j), n), i);
  at = hn::IfThenElseZero(hn::RebindMask(di, active), at);  // inactive lanes read sample 0
  const VI at10 = hn::Add(at, hn::Set(di, 1));
  const VI at01 = hn::Add(at, n);
  const VI at11 = hn::Add(at01, hn::Set(di, 1));
  const float* tangent = c.tangent.data();
  const V t00 = hn::GatherIndex(d, tangent, at), t10 = hn::GatherIndex(d, tangent, at10);
  const V t01 = hn::GatherIndex(d, tangent, at01), t11 = hn::GatherIndex(d, tangent, at11);
  const V lit = hn::Set(d, p.lit_tangent);
  proven = p.skip_lit != 0 ? hn::And(hn::And(hn::Le(t00, lit), hn::Le(t10, lit)),
                                     hn::And(hn::Le(t01, lit), hn::Le(t11, lit)))
                           : hn::FirstN(d, 0);
  proven = hn::And(proven, active);
  const V one = hn::Set(d, 1.0f);
  if (hn::AllTrue(d, hn::Or(proven, hn::Not(active)))) {
    return one;
  }
  const float* heights = c.height.data();
  const V h00 = hn::GatherIndex(d, heights, at), h10 = hn::GatherIndex(d, heights, at10);
  const V h01 = hn::GatherIndex(d, heights, at01), h11 = hn::GatherIndex(d, heights, at11);
  const V surface = Mix(Mix(h00, h10, f), Mix(h01, h11, f), g);
  const V lift = StdMax(hn::Zero(d), hn::Sub(height, surface));
  const float* inv = c.inv_distance.data();
  const V s00 = DiscShare(d, p, hn::Sub(t00, hn::Mul(lift, hn::GatherIndex(d, inv, at))));
  const V s10 = DiscShare(d, p, hn::Sub(t10, hn::Mul(lift, hn::GatherIndex(d, inv, at10))));
  const V s01 = DiscShare(d, p, hn::Sub(t01, hn::Mul(lift, hn::GatherIndex(d, inv, at01))));
  const V s11 = DiscShare(d, p, hn::Sub(t11, hn::Mul(lift, hn::GatherIndex(d, inv, at11))));
  return hn::IfThenElse(proven, one, Mix(Mix(s00, s10, f), Mix(s01, s11, f), g));
}

// sun_visibility for the lanes of `covered`; the others' results are not used.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V SunShareVector(D d, const ShadowParams<float>& p, const SunHorizonCache<float>& c,
                            V dx, V height, V dz, M covered, ShadowWork& work) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const std::size_t pixels = hn::CountTrue(d, covered);
  work.pixels += pixels;
  if (p.sun_set != 0) {
    work.dark += pixels;
    return zero;
  }
  dx = hn::IfThenElseZero(covered, dx);
  dz = hn::IfThenElseZero(covered, dz);
  height = hn::IfThenElseZero(covered, height);
  const V ax = hn::Set(d, p.axis_x), az = hn::Set(d, p.axis_z);
  const V u = hn::Add(hn::Mul(dx, ax), hn::Mul(dz, az));
  const V v = hn::Sub(hn::Mul(dz, ax), hn::Mul(dx, az));
  const V last = hn::Set(d, float(p.resolution - 1));
  // The finest level from first_level whose square holds the point, per lane.
  M found = hn::FirstN(d, 0);
  V fi = zero, fj = zero;
  VI level = hn::Set(di, p.end_level);
  for (int l = p.first_level; l < p.end_level; ++l) {
    if (hn::AllTrue(d, hn::Or(found, hn::Not(covered)))) {
      break;
    }
    const V a = hn::Mul(hn::Sub(u, hn::Set(d, p.origin_u[l])), hn::Set(d, p.inv_spacing[l]));
    const V b = hn::Mul(hn::Sub(v, hn::Set(d, p.origin_v[l])), hn::Set(d, p.inv_spacing[l]));
    const M in = hn::And(hn::And(hn::Ge(a, zero), hn::Lt(a, last)),
                         hn::And(hn::Ge(b, zero), hn::Lt(b, last)));
    const M fresh = hn::AndNot(found, in);
    fi = hn::IfThenElse(fresh, a, fi);
    fj = hn::IfThenElse(fresh, b, fj);
    level = hn::IfThenElse(hn::RebindMask(di, fresh), hn::Set(di, l), level);
    found = hn::Or(found, in);
  }
  const M active = hn::And(found, covered);
  work.outside += hn::CountTrue(d, hn::AndNot(found, covered));
  if (hn::AllFalse(d, active)) {
    return one;
  }
  M proven;
  V share = LevelShare(d, p, c, level, fi, fj, height, active, proven);
  // The blend band along the level's edge, into the next coarser level.
  const V edge = StdMin(StdMin(fi, fj), StdMin(hn::Sub(last, fi), hn::Sub(last, fj)));
  const VI next = hn::Add(level, hn::Set(di, 1));
  M band = hn::And(active, hn::And(hn::Lt(edge, hn::Set(d, p.blend_samples)),
                                   hn::RebindMask(d, hn::Lt(next, hn::Set(di, p.end_level)))));
  if (!hn::AllFalse(d, band)) {
    // Levels past the last one built read entry end_level - 1 (their lanes are not in band).
    const VI entry =
        hn::IfThenElse(hn::Lt(next, hn::Set(di, p.end_level)), next, hn::Set(di, p.end_level - 1));
    const V inv = hn::GatherIndex(d, p.inv_spacing, entry);
    const V a = hn::Mul(hn::Sub(u, hn::GatherIndex(d, p.origin_u, entry)), inv);
    const V b = hn::Mul(hn::Sub(v, hn::GatherIndex(d, p.origin_v, entry)), inv);
    band = hn::And(band, hn::And(hn::And(hn::Ge(a, zero), hn::Lt(a, last)),
                                 hn::And(hn::Ge(b, zero), hn::Lt(b, last))));
    if (!hn::AllFalse(d, band)) {
      M coarse_proven;
      const V coarse = LevelShare(d, p, c, entry, a, b, height, band, coarse_proven);
      share = hn::IfThenElse(
          band, Mix(coarse, share, hn::Mul(edge, hn::Set(d, p.inv_blend_samples))), share);
      proven = hn::Or(hn::AndNot(band, proven), hn::And(band, hn::And(proven, coarse_proven)));
    }
  }
  const M lit = hn::And(active, proven);
  work.lit += hn::CountTrue(d, lit);
  work.evaluated += hn::CountTrue(d, hn::AndNot(proven, active));
  work.dark += hn::CountTrue(d, hn::And(active, hn::Eq(share, zero)));
  return hn::IfThenElse(active, share, one);
}

void SunShares(const ShadowParams<float>& p, const SunHorizonCache<float>& c,
               const std::uint32_t* HWY_RESTRICT covered, const float* HWY_RESTRICT dx,
               const float* HWY_RESTRICT height, const float* HWY_RESTRICT dz, int width,
               int height_px, int stride, float* HWY_RESTRICT share, ShadowWork& total) {
  const hn::ScalableTag<float> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  const int lanes = static_cast<int>(hn::Lanes(d));
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float tail[4][kMaxLanes] = {};
  HWY_ALIGN std::uint32_t tail_covered[kMaxLanes] = {};
  ShadowWork work;
  for (int j = 0; j < height_px; ++j) {
    for (int i = 0; i < width; i += lanes) {
      const std::size_t k = static_cast<std::size_t>(j) * stride + i;
      const int count = width - i < lanes ? width - i : lanes;
      const float *x = dx + k, *y = height + k, *z = dz + k;
      const std::uint32_t* primitive = covered + k;
      if (count < lanes) {  // the last pixels of the row: copies, the other lanes uncovered
        for (int t = 0; t < lanes; ++t) {
          const bool in = t < count;
          tail_covered[t] = in ? covered[k + t] : 0xffffffffu;
          tail[0][t] = in ? dx[k + t] : 0.0f;
          tail[1][t] = in ? height[k + t] : 0.0f;
          tail[2][t] = in ? dz[k + t] : 0.0f;
        }
        x = tail[0];
        y = tail[1];
        z = tail[2];
        primitive = tail_covered;
      }
      const auto m =
          hn::Not(hn::RebindMask(d, hn::Eq(hn::LoadU(du, primitive), hn::Set(du, 0xffffffffu))));
      if (hn::AllFalse(d, m)) {
        continue;
      }
      const auto result =
          SunShareVector(d, p, c, hn::LoadU(d, x), hn::LoadU(d, y), hn::LoadU(d, z), m, work);
      if (count == lanes) {
        hn::BlendedStore(result, m, d, share + k);
      } else {
        hn::StoreU(result, d, tail[3]);
        for (int t = 0; t < count; ++t) {
          if (covered[k + t] != 0xffffffffu) {
            share[k + t] = tail[3][t];
          }
        }
      }
    }
  }
  total += work;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
