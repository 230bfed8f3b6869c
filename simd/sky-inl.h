// Per-target sky and distance fog of core/sky.cc for float, one direction per lane:
// sky_radiance, fog_color and apply_fog with the scalar code's operations in its order; the
// scalar branches (above the horizon, no fog) become masks, the atmosphere's (a frame's
// constant) stays a branch.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_SKY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SKY_INL_H_
#undef RELIEF_SIMD_SKY_INL_H_
#else
#define RELIEF_SIMD_SKY_INL_H_
#endif

#include <hwy/highway.h>

#include "core/stage_params.h"
#include "simd/atmosphere-inl.h"
#include "simd/det_math-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/skybox-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// power_of_half_cosine (sky.cc): clamp01((1 + c) 0.5) squared `squarings` times.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V PowerOfHalfCosine(D d, V c, int squarings) {
  V x = Clamp01(d, hn::Mul(hn::Add(hn::Set(d, 1.0f), c), hn::Set(d, 0.5f)));
  for (int k = 0; k < squarings; ++k) {
    x = hn::Mul(x, x);
  }
  return x;
}

// sun_light (sky.cc): the sun disc times `disc_share` and its halo in directions `dir`.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> SunLight(D d, const ShadeParams<float>& p, const V3<V>& dir, V disc_share) {
  const V c = Dot3(dir, Set3(d, p.sun_direction));
  const float inner = p.sun_cos_inner, outer = p.sun_cos_outer;
  V disc;
  if (inner > outer) {
    disc = Smooth01(d, hn::Div(hn::Sub(c, hn::Set(d, outer)), hn::Set(d, inner - outer)));
  } else {
    disc = hn::IfThenElseZero(hn::Ge(c, hn::Set(d, inner)), hn::Set(d, 1.0f));
  }
  if (p.atmosphere != 0) {
    return Scale3(Set3(d, p.sun), hn::Mul(hn::Mul(hn::Set(d, 20.0f), disc), disc_share));
  }
  const V halo = hn::Mul(hn::Set(d, float(0.06)), PowerOfHalfCosine(d, c, 5));
  const V k = hn::Add(hn::Mul(hn::Mul(hn::Set(d, 20.0f), disc), disc_share), halo);
  return Scale3(Set3(d, p.sun), k);
}

// sky_radiance (sky.cc) of unit directions `dir`: the skybox where p.skybox is set and `box`
// holds its faces, else the gradient; plus the sun, its disc times `disc_share` (1: the same
// bits as without).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> SkyRadiance(D d, const ShadeParams<float>& p, const SkyboxView& box,
                             const V3<V>& dir, V disc_share) {
  if (p.skybox != 0 && box.texels != nullptr) {
    const V3<V> color = SkyboxRadiance(d, box, dir);
    return p.skybox_sun != 0 ? Add3(color, SunLight(d, p, dir, disc_share)) : color;
  }
  if (p.atmosphere != 0) {
    return Add3(AtmosphereSky(d, p, dir), SunLight(d, p, dir, disc_share));
  }
  const V3<V> horizon = Set3(d, p.horizon);
  V3<V> color = horizon;
  const auto above = hn::Gt(dir.y, hn::Zero(d));
  if (!hn::AllFalse(d, above)) {
    // sqrt's domain is the lanes above the horizon; the others' result is discarded.
    color = Select3(above, Mix3(horizon, Set3(d, p.zenith), hn::Sqrt(dir.y)), horizon);
  }
  return Add3(color, SunLight(d, p, dir, disc_share));
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> SkyRadiance(D d, const ShadeParams<float>& p, const SkyboxView& box,
                             const V3<V>& dir) {
  return SkyRadiance(d, p, box, dir, hn::Set(d, 1.0f));
}

// fog_color (sky.cc): the horizon plus the sun's glow.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> FogColor(D d, const ShadeParams<float>& p, const V3<V>& dir) {
  if (p.atmosphere != 0) {
    return AtmosphereOver(d, p, Set3(d, 0.0f, 0.0f, 0.0f), dir,
                          hn::Set(d, float(limits::kMaxCameraRelativeDistance)));
  }
  const V c = Dot3(dir, Set3(d, p.sun_direction));
  return Add3(Set3(d, p.horizon),
              Scale3(Set3(d, p.sun), hn::Mul(hn::Set(d, float(0.05)), PowerOfHalfCosine(d, c, 3))));
}

// apply_fog (sky.cc): clear = exp2_det(-density distance); the radiance itself where clear is
// not below 1, else mix(fog colour, radiance, clear).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> ApplyFog(D d, const ShadeParams<float>& p, const V3<V>& radiance, const V3<V>& dir,
                          V distance) {
  if (p.atmosphere != 0) {
    return AtmosphereOver(d, p, radiance, dir, distance);
  }
  const V clear = Exp2Det(d, hn::Mul(hn::Set(d, -p.fog_density_log2), distance));
  const auto fogged = hn::Lt(clear, hn::Set(d, 1.0f));
  if (hn::AllFalse(d, fogged)) {
    return radiance;
  }
  return Select3(fogged, Mix3(FogColor(d, p, dir), radiance, clear), radiance);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
