// Stage 8's per-target entries compiled out of line (simd/shade_water.cc,
// simd/shade_background.cc and simd/clouds.cc, for the same targets as simd/shade.cc): the
// water of a vector of pixels, the background of one, and the cloud layer's sun share and
// layer over a radiance (simd/clouds-inl.h). Declarations only, so that each translation unit
// compiles its part of the stage once per target: the parts build side by side, and none of
// them is the one long serial step of a build (the sanitizer build above all).
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_SHADE_CALLS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SHADE_CALLS_INL_H_
#undef RELIEF_SIMD_SHADE_CALLS_INL_H_
#else
#define RELIEF_SIMD_SHADE_CALLS_INL_H_
#endif

#include <hwy/highway.h>

#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/lattice-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/skybox-inl.h"
#include "simd/textured_shade-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using ShadeTag = hn::ScalableTag<float>;
using ShadeVec = hn::Vec<ShadeTag>;
using ShadeMask = hn::Mask<ShadeTag>;

// shade_water (core/water.cc) for the lanes of `active` (simd/water-inl.h's ShadeWater; the
// other lanes' results are unspecified).
V3<ShadeVec> ShadeWaterLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const SkyboxView& skybox, const V3<ShadeVec>& view,
                             ShadeVec surface_distance, ShadeVec depth, const V3<ShadeVec>& ground,
                             ShadeVec footprint, ShadeVec sun_share, const V3<ShadeVec>& terrain,
                             ShadeVec terrain_weight, ShadeMask active, ShadeWork& work);

// background_radiance (core/shade.cc) for the lanes of `background`, pixels (px0 + lane, py)
// (simd/background-inl.h's BackgroundRadiance; zero elsewhere or unspecified).
V3<ShadeVec> BackgroundLanes(const ShadeContext& ctx, int px0, int py, ShadeMask background,
                             ShadeWork& work);

// cloud_sun_share (core/clouds.cc) of the camera-relative points `position` of the lanes of
// `active`; 1 elsewhere.
ShadeVec CloudSunShareLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                            const V3<ShadeVec>& position, ShadeVec footprint, ShadeMask active,
                            ShadeWork& work);

// clouds_over_from (core/clouds.cc) for the lanes of `active`: `radiance` seen along unit
// `dir` from `origin` (`origin_distance` from the camera; 0 and 0 for the camera itself) up
// to `end`; the radiance itself elsewhere.
V3<ShadeVec> CloudsOverLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const V3<ShadeVec>& radiance, const V3<ShadeVec>& origin,
                             ShadeVec origin_distance, const V3<ShadeVec>& dir, ShadeVec end,
                             ShadeMask active, ShadeWork& work);

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
