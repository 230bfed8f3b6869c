// The cloud layer's per-target entries as the shading calls them (simd/clouds-inl.h, compiled
// out of line in simd/clouds.cc for the same targets): the sun's share through the layer and
// the layer over a radiance, one pixel per lane of a full float vector. Declarations only, so
// that simd/shade.cc does not compile the layer's kernels again in each of the four places
// that read them.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_CLOUD_CALLS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_CLOUD_CALLS_INL_H_
#undef RELIEF_SIMD_CLOUD_CALLS_INL_H_
#else
#define RELIEF_SIMD_CLOUD_CALLS_INL_H_
#endif

#include <hwy/highway.h>

#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/lattice-inl.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using CloudTag = hn::ScalableTag<float>;
using CloudVec = hn::Vec<CloudTag>;
using CloudMask = hn::Mask<CloudTag>;

// cloud_sun_share (core/clouds.cc) of the camera-relative points `position` of the lanes of
// `active`; 1 elsewhere.
CloudVec CloudSunShareLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                            const V3<CloudVec>& position, CloudVec footprint, CloudMask active,
                            ShadeWork& work);

// clouds_over_from (core/clouds.cc) for the lanes of `active`: `radiance` seen along unit
// `dir` from `origin` (`origin_distance` from the camera; 0 and 0 for the camera itself) up
// to `end`; the radiance itself elsewhere.
V3<CloudVec> CloudsOverLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const V3<CloudVec>& radiance, const V3<CloudVec>& origin,
                             CloudVec origin_distance, const V3<CloudVec>& dir, CloudVec end,
                             CloudMask active, ShadeWork& work);

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
