// Highway's per-target compilation of the cloud layer (simd/clouds-inl.h), out of line: the
// entries simd/shade_calls-inl.h declares for the shading.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/clouds.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/clouds-inl.h"
#include "simd/shade_calls-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

ShadeVec CloudSunShareLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                            const V3<ShadeVec>& position, ShadeVec footprint, ShadeMask active,
                            ShadeWork& work) {
  return CloudSunShare(ShadeTag(), p, lattice, position, footprint, active, work);
}

V3<ShadeVec> CloudsOverLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const V3<ShadeVec>& radiance, const V3<ShadeVec>& origin,
                             ShadeVec origin_distance, const V3<ShadeVec>& dir, ShadeVec end,
                             ShadeMask active, ShadeWork& work) {
  return CloudsOverFrom(ShadeTag(), p, lattice, radiance, origin, origin_distance, dir, end, active,
                        work);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();
