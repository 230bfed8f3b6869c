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
#include "simd/cache_level-inl.h"
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
  V f, g;
  const VI at = CacheSampleIndex(d, c, level, fi, fj, active, f, g);
  const VI n = hn::Set(di, c.resolution);
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
  using VI = hn::Vec<hn::RebindToSigned<D>>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const std::size_t pixels = hn::CountTrue(d, covered);
  work.pixels += pixels;
  if (p.sun_set != 0) {
    work.dark += pixels;
    return zero;
  }
  height = hn::IfThenElseZero(covered, height);
  // The finest level from first_level whose square holds the point, per lane.
  V u, v, fi, fj;
  VI level;
  const M active = LocateInCache(d, p, dx, dz, covered, u, v, level, fi, fj, work.outside);
  if (hn::AllFalse(d, active)) {
    return one;
  }
  M proven;
  V share = LevelShare(d, p, c, level, fi, fj, height, active, proven);
  // The blend band along the level's edge, into the next coarser level.
  VI entry;
  V a, b, edge;
  const M band = CoarserBand(d, p, u, v, level, fi, fj, active, entry, a, b, edge);
  if (!hn::AllFalse(d, band)) {
    M coarse_proven;
    const V coarse = LevelShare(d, p, c, entry, a, b, height, band, coarse_proven);
    share = hn::IfThenElse(band, Mix(coarse, share, hn::Mul(edge, hn::Set(d, p.inv_blend_samples))),
                           share);
    proven = hn::Or(hn::AndNot(band, proven), hn::And(band, hn::And(proven, coarse_proven)));
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
  ShadowWork work;
  const float* const streams[3] = {dx, height, dz};
  ForEachCoveredVector(d, covered, streams, width, height_px, stride, share,
                       [&](auto m, const float* const* in) {
                         return SunShareVector(d, p, c, hn::LoadU(d, in[0]), hn::LoadU(d, in[1]),
                                               hn::LoadU(d, in[2]), m, work);
                       });
  total += work;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
