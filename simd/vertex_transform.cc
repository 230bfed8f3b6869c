// Highway's per-target compilation of simd/vertex_transform-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/vertex_transform.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/vertex_transform-inl.h"

#if HWY_ONCE
#include "simd/vertex_transform.h"

namespace relief::simd {

HWY_EXPORT(TransformVertices);
HWY_EXPORT(LightVertices);

void transform_vertices(const TransformParams<float>& params, IndexRange range,
                        std::span<const float> dx, std::span<const float> dz,
                        std::span<const float> height, std::span<const std::uint8_t> need,
                        ClipSpans<float> clip) {
  HWY_DYNAMIC_DISPATCH(TransformVertices)
  (params, range, dx.data(), dz.data(), height.data(), need.empty() ? nullptr : need.data(),
   clip.x.data(), clip.y.data(), clip.z.data(), clip.w.data());
}

void light_vertices(const TransformParams<float>& params, IndexRange range,
                    std::span<const float> nx, std::span<const float> ny, std::span<const float> nz,
                    std::span<const std::uint8_t> need, std::span<float> lambert) {
  HWY_DYNAMIC_DISPATCH(LightVertices)
  (params, range, nx.data(), ny.data(), nz.data(), need.empty() ? nullptr : need.data(),
   lambert.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
