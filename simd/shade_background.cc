// Highway's per-target compilation of the background of stage 8 (simd/background-inl.h), out of
// line: the entry simd/shade_calls-inl.h declares for simd/shade.cc's pixels that no terrain
// covers.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/shade_background.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/background-inl.h"
#include "simd/shade_calls-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

V3<ShadeVec> BackgroundLanes(const ShadeContext& ctx, int px0, int py, ShadeMask background,
                             ShadeWork& work) {
  return BackgroundRadiance(ShadeTag(), ctx, px0, py, background, work);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();
