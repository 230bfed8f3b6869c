// Highway's per-target compilation of simd/vertex_snap-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/vertex_snap.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/vertex_snap-inl.h"

#if HWY_ONCE
#include "simd/vertex_snap.h"

namespace relief::simd {

HWY_EXPORT(WindowVertices);
HWY_EXPORT(SnapVertices);

void window_vertices(const SnapConstants& constants, const float* x, const float* y, const float* z,
                     const float* w, const std::uint8_t* valid, const std::uint8_t* need,
                     std::size_t n, float* window_x, float* window_y, float* window_z,
                     std::uint32_t* bits) {
  HWY_DYNAMIC_DISPATCH(WindowVertices)
  (constants, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
}

void snap_vertices(std::size_t n, const std::uint32_t* bits, const float* window_x,
                   const float* window_y, std::uint8_t* flags, std::uint8_t* outcode,
                   float* floor_x, float* floor_y, std::int32_t* fx, std::int32_t* fy) {
  HWY_DYNAMIC_DISPATCH(SnapVertices)
  (n, bits, window_x, window_y, flags, outcode, floor_x, floor_y, fx, fy);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
