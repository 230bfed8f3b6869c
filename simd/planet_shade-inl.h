// Per-target planet parts of stage 8 (core/planet_shading.h, core/shade.cc's planet branches)
// for float, one pixel per lane: the rotation into a point's local frame, and the background
// of a planet frame (the water sphere, the datum sphere's fog, or the sky read from the limb),
// with the scalar code's operations in its order.
// Included by simd/shade-inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_PLANET_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PLANET_SHADE_INL_H_
#undef RELIEF_SIMD_PLANET_SHADE_INL_H_
#else
#define RELIEF_SIMD_PLANET_SHADE_INL_H_
#endif

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/planet_shading.h"
#include "core/stage_params.h"
#include "simd/planet_rays-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"
#include "simd/textured_shade-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// to_local_frame (planet_shading.h): v rotated by the rotation taking the unit `up` to
// (0, 1, 0); v itself where up.y <= -0.999. The products with w.y = 0 are kept, as the scalar
// code forms them (0 * x is not folded without fast-math: -0 and NaN).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> ToLocalFrame(D d, const V3<V>& v, const V3<V>& up) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto rotate = hn::Gt(up.y, hn::Set(d, -0.999f));
  const V3<V> w{hn::Neg(up.z), zero, up.x};
  const auto cross = [](const V3<V>& a, const V3<V>& b) {
    return V3<V>{hn::Sub(hn::Mul(a.y, b.z), hn::Mul(a.z, b.y)),
                 hn::Sub(hn::Mul(a.z, b.x), hn::Mul(a.x, b.z)),
                 hn::Sub(hn::Mul(a.x, b.y), hn::Mul(a.y, b.x))};
  };
  const V3<V> wv = cross(w, v);
  const V3<V> wwv = cross(w, wv);
  // Domain of the division: 1 + c >= 0.001 in the lanes that use it; the others divide by a
  // value they discard (1 where up.y is -1 or below: finite).
  const V k = hn::Div(one, hn::IfThenElse(rotate, hn::Add(one, up.y), one));
  const V3<V> rotated = Add3(Add3(v, wv), Scale3(wwv, k));
  return Select3(rotate, rotated, v);
}

// planet_background (shade.cc) for the lanes of `background`, pixels (px0 + lane, py), whose
// view rays rounded to float and normalised are `dir`. The sphere tests and the sky's
// direction from the limb run in double lanes (PlanetRays); the shading in float lanes.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> PlanetBackground(D d, const ShadeContext& ctx, int px0, int py, const V3<V>& dir,
                                  M background, ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d);
  const PlanetRayVectors<D> rays = PlanetRays(d, p, px0, py);
  const M water = hn::And(background, rays.water);
  const M ground = hn::AndNot(rays.water, hn::And(background, rays.ground));
  const M sky = hn::AndNot(hn::Or(rays.water, rays.ground), background);
  V3<V> result{zero, zero, zero};
  if (!hn::AllFalse(d, sky)) {
    result = SkyRadiance(d, p, ctx.skybox, rays.sky);
  }
  if (!hn::AllFalse(d, ground)) {
    result = Select3(ground, FogColor(d, p, dir), result);
  }
  const std::size_t count = hn::CountTrue(d, water);
  if (count != 0) {
    const V3<V> open = OpenWater(d, p, ctx.lattice, ctx.skybox, ToLocalFrame(d, dir, rays.up), dir,
                                 rays.surface, water, count, work);
    result = Select3(water, open, result);
  }
  return result;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
