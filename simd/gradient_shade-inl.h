// Per-target stage-8 pieces of simd/shade-inl.h for shading.mode = gradient
// (core/gradient_shade.h): the height gradient's colour and the Gouraud light, operation by
// operation as the scalar functions, one pixel per lane.
#if defined(RELIEF_SIMD_GRADIENT_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_GRADIENT_SHADE_INL_H_
#undef RELIEF_SIMD_GRADIENT_SHADE_INL_H_
#else
#define RELIEF_SIMD_GRADIENT_SHADE_INL_H_
#endif

#include <hwy/highway.h>

#include "core/stage_params.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// gradient_albedo: every segment evaluated, each lane keeping the last one whose lower stop
// lies at or below its height (the scalar loop's `continue` as a mask).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> GradientAlbedo(D d, const ShadeParams<float>& p, V h) {
  const V one = hn::Set(d, 1.0f);
  V3<V> color = Set3(d, p.gradient_color[0]);
  for (int i = 0; i + 1 < p.gradient_count; ++i) {
    const auto above = hn::Ge(h, hn::Set(d, p.gradient_height[i]));
    if (hn::AllFalse(d, above)) {
      continue;
    }
    const V ramp =
        hn::Mul(hn::Sub(h, hn::Set(d, p.gradient_height[i])), hn::Set(d, p.gradient_inv_span[i]));
    const V partial = hn::IfThenElse(hn::Lt(ramp, one), ramp, one);
    const V t = hn::IfThenElse(hn::Ge(h, hn::Set(d, p.gradient_height[i + 1])), one, partial);
    const V3<V> low = Set3(d, p.gradient_color[i]);
    const V3<V> segment = Add3(low, Scale3(Sub3(Set3(d, p.gradient_color[i + 1]), low), t));
    color = Select3(above, segment, color);
  }
  return color;
}

// gouraud_light: albedo (sun lambert share + mix(ground, sky, (1/2 + ny / 2) sky share) +
// ambient).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> GouraudLight(D d, const ShadeParams<float>& p, const V3<V>& albedo, V lambert,
                              V ny, V sun_share, V sky_share) {
  const V sunlit = hn::Mul(lambert, sun_share);
  const V half = hn::Set(d, 0.5f);
  const V3<V> hemisphere = Mix3(Set3(d, p.ground_light), Set3(d, p.sky_light),
                                hn::Mul(hn::Add(half, hn::Mul(half, ny)), sky_share));
  const V ambient = hn::Set(d, p.ambient);
  return Mul3(albedo, Add3(Add3(Scale3(Set3(d, p.sun), sunlit), hemisphere),
                           V3<V>{ambient, ambient, ambient}));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
