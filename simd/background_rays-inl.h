// Per-target view rays of the background (core/shade.cc, background_radiance): one pixel per
// lane, formed in double as the scalar code forms them and rounded once to float.
// Included by simd/shade-inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_BACKGROUND_RAYS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_BACKGROUND_RAYS_INL_H_
#undef RELIEF_SIMD_BACKGROUND_RAYS_INL_H_
#else
#define RELIEF_SIMD_BACKGROUND_RAYS_INL_H_
#endif

#include <hwy/highway.h>

#include "core/stage_params.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// The background's view rays of pixels (px0 + lane, py), formed in double as
// background_radiance forms them and rounded once to float.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> BackgroundRays(D d, const ShadeParams<float>& p, int px0, int py) {
  const double ndc_y = 2.0 * (py + 0.5) / p.height - 1.0;
  const double sy = ndc_y * p.tan_half_fov_y;
#if HWY_TARGET == HWY_SCALAR
  const double ndc_x = 2.0 * (px0 + 0.5) / p.width - 1.0;
  const double sx = ndc_x * p.tan_half_fov_x;
  float ray[3];
  for (int c = 0; c < 3; ++c) {
    ray[c] = static_cast<float>((p.forward[c] + sx * p.right[c]) + sy * p.up[c]);
  }
  return Set3(d, ray[0], ray[1], ray[2]);
#else
  const hn::Half<D> dh;
  const hn::Rebind<double, decltype(dh)> dd;
  const std::size_t half = hn::Lanes(dh);
  const auto two = hn::Set(dd, 2.0), point_five = hn::Set(dd, 0.5), one = hn::Set(dd, 1.0);
  const auto width = hn::Set(dd, double(p.width));
  const auto tan_x = hn::Set(dd, p.tan_half_fov_x);
  const auto sy_v = hn::Set(dd, sy);
  hn::Vec<decltype(dh)> parts[2][3];
  for (int h = 0; h < 2; ++h) {
    const auto px = hn::Iota(dd, double(px0) + double(h * half));
    const auto ndc_x = hn::Sub(hn::Div(hn::Mul(two, hn::Add(px, point_five)), width), one);
    const auto sx = hn::Mul(ndc_x, tan_x);
    for (int c = 0; c < 3; ++c) {
      const auto ray =
          hn::Add(hn::Add(hn::Set(dd, p.forward[c]), hn::Mul(sx, hn::Set(dd, p.right[c]))),
                  hn::Mul(sy_v, hn::Set(dd, p.up[c])));
      parts[h][c] = hn::DemoteTo(dh, ray);
    }
  }
  return {hn::Combine(d, parts[1][0], parts[0][0]), hn::Combine(d, parts[1][1], parts[0][1]),
          hn::Combine(d, parts[1][2], parts[0][2])};
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
