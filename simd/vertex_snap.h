// The per-vertex passes of the triangle set-up (stage 6: the window transform, the clip
// outcode's near, far and guard-band decisions, snapping to the 16.8 grid) as Highway kernels:
// raster's prepare_vertices loops (raster/vertex_prepare.cc), lane by lane, bit for bit.
// raster::SnapKernels is their signature; pipeline/ connects the two.
#pragma once

#include <cstddef>
#include <cstdint>

namespace relief::simd {

// raster::SnapConstants: the guard band in clip units and the viewport transform.
struct SnapConstants {
  float guard_x, guard_y;
  float scale_x, scale_y, translate_x, translate_y;
};

// raster::PreparedVertices' bits.
namespace snap_bits {
inline constexpr std::uint32_t kValid = 1, kDrawn = 2, kPlain = 4, kSnapped = 8;
inline constexpr std::uint32_t kOutcodeShift = 8, kOutcodeMask = 0x3f;
inline constexpr std::uint32_t kGuardUndecided = 1u << 16;
}  // namespace snap_bits

// The first pass: window coordinates and the intermediate bits of n vertices (valid, need:
// null for all valid, all drawn).
void window_vertices(const SnapConstants& constants, const float* x, const float* y, const float* z,
                     const float* w, const std::uint8_t* valid, const std::uint8_t* need,
                     std::size_t n, float* window_x, float* window_y, float* window_z,
                     std::uint32_t* bits);

// The last pass: flags, outcodes, floors and the snapped 16.8 coordinates.
void snap_vertices(std::size_t n, const std::uint32_t* bits, const float* window_x,
                   const float* window_y, std::uint8_t* flags, std::uint8_t* outcode,
                   float* floor_x, float* floor_y, std::int32_t* fx, std::int32_t* fy);

}  // namespace relief::simd
