// Highway's per-target compilation of simd/sketch-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/sketch.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/sketch-inl.h"

#if HWY_ONCE
#include "simd/sketch.h"

namespace relief::simd {

HWY_EXPORT(AddSketch);

void add_sketch(const SketchParams<float>& params, std::span<const float> heights, IndexRange range,
                std::span<const float> dx, std::span<const float> dz, std::span<const float> nu,
                std::span<const std::uint8_t> mask, std::span<float> height) {
  HWY_DYNAMIC_DISPATCH(AddSketch)
  (params, heights.data(), range, dx.data(), dz.data(), nu.empty() ? nullptr : nu.data(),
   mask.empty() ? nullptr : mask.data(), height.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
