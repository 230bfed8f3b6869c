// Highway's per-target compilation of simd/reflection_rays-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/reflection_rays.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/reflection_rays-inl.h"

#if HWY_ONCE
#include "simd/reflection_rays.h"

namespace relief::simd {

HWY_EXPORT(ReflectionRays);

void reflection_rays(const ShadeParams<float>& p, const NoiseLattice& lattice,
                     const std::uint32_t* primitive, const float* dx, const float* height,
                     const float* dz, const float* depth, int count, const ReflectionRayRow& row) {
  if (count <= 0) {
    return;
  }
  HWY_DYNAMIC_DISPATCH(ReflectionRays)(p, lattice, primitive, dx, height, dz, depth, count, row);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
