// Per-target background of stage 8 (core/shade.cc's background_radiance) for float, one pixel
// per lane: the sky, open water below the horizon, a planet's water sphere, datum fog and limb,
// and the cloud layer over them, with the scalar code's operations in its order. Compiled once
// per target in simd/shade_background.cc; simd/shade.cc calls it through BackgroundLanes.
// Included by simd/shade_background.cc inside its per-target section (Highway's re-inclusion
// guard).
#if defined(RELIEF_SIMD_BACKGROUND_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_BACKGROUND_INL_H_
#undef RELIEF_SIMD_BACKGROUND_INL_H_
#else
#define RELIEF_SIMD_BACKGROUND_INL_H_
#endif

#include <cstddef>

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/background_rays-inl.h"
#include "simd/planet_rays-inl.h"
#include "simd/planet_shade-inl.h"
#include "simd/shade_calls-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"
#include "simd/textured_shade-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// open_water (shade.cc) for the lanes of `active`, `count` of them: open water `surface` along
// the view ray `dir`, seen as `view` in the water's own frame, then fogged along dir; counted
// as the scalar code counts it.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> OpenWater(D d, const ShadeParams<float>& p, const LatticeView& lattice,
                           const SkyboxView& skybox, const V3<V>& view, const V3<V>& dir, V surface,
                           M active, std::size_t count, ShadeWork& work) {
  const V zero = hn::Zero(d);
  const V footprint = SurfaceFootprint(d, p, surface, view.y);
  const V3<V> open =
      ShadeWaterLanes(p, lattice, skybox, view, surface, hn::Set(d, 1e6f), V3<V>{zero, zero, zero},
                      footprint, hn::Set(d, 1.0f), V3<V>{zero, zero, zero}, zero, active, work);
  work.water_pixels += count;
  if (!p.fog_enabled) {
    return open;
  }
  work.fogged_pixels += count;
  return ApplyFog(d, p, open, dir, surface);
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

// background_radiance (shade.cc) for the lanes of `background`, pixels (px0 + lane, py).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> BackgroundRadiance(D d, const ShadeContext& ctx, int px0, int py, M background,
                                    ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d);
  work.background_pixels += hn::CountTrue(d, background);
  const V3<V> dir = NormalizeOr(d, BackgroundRays(d, p, px0, py), Set3(d, p.camera_forward));
  if (p.planet_center_distance > 0.0) {
    return PlanetBackground(d, ctx, px0, py, dir, background, work);
  }
  const M below = hn::Lt(dir.y, zero);
  const M below_lanes = hn::And(background, below);
  V3<V> result{zero, zero, zero};
  if (!hn::AllFalse(d, hn::AndNot(below, background))) {
    result = SkyRadiance(d, p, ctx.skybox, dir);
  }
  // The sky and the fog lie beyond every distance; open water at its surface (shade.cc).
  V end = hn::Set(d, float(limits::kMaxCameraRelativeDistance));
  const std::size_t count = hn::CountTrue(d, below_lanes);
  if (count != 0) {
    const V surface = hn::Div(hn::Set(d, p.water_level), dir.y);
    const V3<V> ground = p.water_enabled ? OpenWater(d, p, ctx.lattice, ctx.skybox, dir, dir,
                                                     surface, below_lanes, count, work)
                                         : FogColor(d, p, dir);
    result = Select3(below, ground, result);
    if (p.water_enabled) {
      end = hn::IfThenElse(below, surface, end);
    } else if (p.clouds) {  // terrain past the far distance, no lower than the frame's lowest
      end = hn::IfThenElse(below, StdMin(end, hn::Div(hn::Set(d, p.cloud_ground), dir.y)), end);
    }
  }
  return p.clouds ? CloudsOverLanes(p, ctx.lattice, result, V3<V>{zero, zero, zero}, zero, dir, end,
                                    background, work)
                  : result;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
