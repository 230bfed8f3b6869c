// Per-target body of simd/sky_share.h: sky_visibility<float> (core/sky_horizons.cc) on a vector
// of pixels of one row. Each lane does the scalar code's operations for its pixel in the scalar
// code's order; the level search and blend band are the sun's kernel's (cache_level-inl.h), the
// four samples' reads gathers; lanes not covered are zeroed first and gather index 0. The
// scalar a + (b - a) f is shade_vec3-inl.h's Mix, a + f (b - a): a product rounds alike in
// either order.
#if defined(RELIEF_SIMD_SKY_SHARE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SKY_SHARE_INL_H_
#undef RELIEF_SIMD_SKY_SHARE_INL_H_
#else
#define RELIEF_SIMD_SKY_SHARE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/sky_horizons.h"
#include "core/sun_horizons.h"
#include "simd/cache_level-inl.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// sky_visibility's level value: the four samples around each lane's point, bilinearly.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE V LevelSky(D d, const SunHorizonCache<float>& c, VI level, V fi, V fj, M active) {
  const hn::RebindToSigned<D> di;
  V f, g;
  const VI at = CacheSampleIndex(d, c, level, fi, fj, active, f, g);
  const VI n = hn::Set(di, c.resolution);
  const VI at01 = hn::Add(at, n);
  const float* sky = c.sky.data();
  const V s00 = hn::GatherIndex(d, sky, at);
  const V s10 = hn::GatherIndex(d, sky, hn::Add(at, hn::Set(di, 1)));
  const V s01 = hn::GatherIndex(d, sky, at01);
  const V s11 = hn::GatherIndex(d, sky, hn::Add(at01, hn::Set(di, 1)));
  return Mix(Mix(s00, s10, f), Mix(s01, s11, f), g);
}

// sky_visibility for the lanes of `covered`; the others' results are not used.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V SkyShareVector(D d, const ShadowParams<float>& p, const SunHorizonCache<float>& c,
                            V dx, V dz, M covered, SkyWork& work) {
  using VI = hn::Vec<hn::RebindToSigned<D>>;
  const V one = hn::Set(d, 1.0f);
  work.pixels += hn::CountTrue(d, covered);
  V u, v, fi, fj;
  VI level;
  const M active = LocateInCache(d, p, dx, dz, covered, u, v, level, fi, fj, work.outside);
  if (hn::AllFalse(d, active)) {
    return one;
  }
  V open = LevelSky(d, c, level, fi, fj, active);
  VI entry;
  V a, b, edge;
  const M band = CoarserBand(d, p, u, v, level, fi, fj, active, entry, a, b, edge);
  if (!hn::AllFalse(d, band)) {
    const V coarse = LevelSky(d, c, entry, a, b, band);
    open = hn::IfThenElse(band, Mix(coarse, open, hn::Mul(edge, hn::Set(d, p.inv_blend_samples))),
                          open);
  }
  work.open += hn::CountTrue(d, hn::And(active, hn::Eq(open, one)));
  return hn::IfThenElse(active, open, one);
}

void SkyShares(const ShadowParams<float>& p, const SunHorizonCache<float>& c,
               const std::uint32_t* HWY_RESTRICT covered, const float* HWY_RESTRICT dx,
               const float* HWY_RESTRICT dz, int width, int height_px, int stride,
               float* HWY_RESTRICT share, SkyWork& total) {
  const hn::ScalableTag<float> d;
  SkyWork work;
  const float* const streams[2] = {dx, dz};
  ForEachCoveredVector(
      d, covered, streams, width, height_px, stride, share, [&](auto m, const float* const* in) {
        return SkyShareVector(d, p, c, hn::LoadU(d, in[0]), hn::LoadU(d, in[1]), m, work);
      });
  total += work;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
