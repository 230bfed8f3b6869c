// Highway's per-target compilation of simd/srgb-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/srgb.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/srgb-inl.h"

#if HWY_ONCE
#include "simd/srgb.h"

namespace relief::simd {

HWY_EXPORT(EncodeSrgb);

void encode_srgb(std::span<const float> linear, std::span<std::uint8_t> out) {
  HWY_DYNAMIC_DISPATCH(EncodeSrgb)(linear.data(), out.data(), linear.size());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
