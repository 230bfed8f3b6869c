// Highway's per-target compilation of simd/vertex_outcodes-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/vertex_outcodes.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/vertex_outcodes-inl.h"

#if HWY_ONCE
#include "simd/vertex_outcodes.h"

namespace relief::simd {

HWY_EXPORT(VertexOutcodes);

void vertex_outcodes(const CullParams<float>& params, RowRange rows, std::span<const float> dx,
                     std::span<const float> dz, std::span<const float> height,
                     std::span<const std::uint8_t> valid, std::span<std::uint8_t> outcode) {
  HWY_DYNAMIC_DISPATCH(VertexOutcodes)
  (params, rows, dx.data(), dz.data(), height.empty() ? nullptr : height.data(), valid.data(),
   outcode.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
