// Highway's per-target compilation of simd/shade-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/shade.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/shade-inl.h"

#if HWY_ONCE
#include "simd/shade.h"

namespace relief::simd {

HWY_EXPORT(ShadeRect);

void shade_rect(const ShadeParams<float>& p, const ShadeResources& r, const ShadingInputs& in,
                int x0, int y0, int width, int height, int stride, std::span<float> rgb,
                ShadeWork& work) {
  if (width <= 0 || height <= 0) {
    return;
  }
  HWY_DYNAMIC_DISPATCH(ShadeRect)(p, r, in, x0, y0, width, height, stride, rgb.data(), work);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
