// Highway's per-target compilation of the cloud layer (simd/clouds-inl.h), out of line: the
// entries simd/cloud_calls-inl.h declares for the shading of simd/shade.cc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/clouds.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/cloud_calls-inl.h"
#include "simd/clouds-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

CloudVec CloudSunShareLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                            const V3<CloudVec>& position, CloudVec footprint, CloudMask active,
                            ShadeWork& work) {
  return CloudSunShare(CloudTag(), p, lattice, position, footprint, active, work);
}

V3<CloudVec> CloudsOverLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const V3<CloudVec>& radiance, const V3<CloudVec>& origin,
                             CloudVec origin_distance, const V3<CloudVec>& dir, CloudVec end,
                             CloudMask active, ShadeWork& work) {
  return CloudsOverFrom(CloudTag(), p, lattice, radiance, origin, origin_distance, dir, end, active,
                        work);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();
