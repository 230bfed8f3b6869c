// Highway's per-target compilation of the water of stage 8 (simd/water-inl.h), out of line: the
// entry simd/shade_calls-inl.h declares for the terrain under water (simd/shade.cc) and for open
// water (simd/shade_background.cc).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/shade_water.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/shade_calls-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

V3<ShadeVec> ShadeWaterLanes(const ShadeParams<float>& p, const LatticeView& lattice,
                             const SkyboxView& skybox, const V3<ShadeVec>& view,
                             ShadeVec surface_distance, ShadeVec depth, const V3<ShadeVec>& ground,
                             ShadeVec footprint, ShadeVec sun_share, const V3<ShadeVec>& terrain,
                             ShadeVec terrain_weight, ShadeMask active, ShadeWork& work) {
  return ShadeWater(ShadeTag(), p, lattice, skybox, view, surface_distance, depth, ground,
                    footprint, sun_share, terrain, terrain_weight, active, work);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();
