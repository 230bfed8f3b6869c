#include "pipeline/simd_setup.h"

#include "simd/vertex_snap.h"

namespace relief {

namespace {

// The two sides name the same bits.
static_assert(raster::PreparedVertices::kValid == simd::snap_bits::kValid &&
              raster::PreparedVertices::kDrawn == simd::snap_bits::kDrawn &&
              raster::PreparedVertices::kPlain == simd::snap_bits::kPlain &&
              raster::PreparedVertices::kSnapped == simd::snap_bits::kSnapped &&
              raster::PreparedVertices::kOutcodeShift == simd::snap_bits::kOutcodeShift &&
              raster::PreparedVertices::kGuardUndecided == simd::snap_bits::kGuardUndecided &&
              raster::kClipOutcodeMask == simd::snap_bits::kOutcodeMask);

void window_pass(const raster::SnapConstants& c, const float* x, const float* y, const float* z,
                 const float* w, const std::uint8_t* valid, const std::uint8_t* need, std::size_t n,
                 float* window_x, float* window_y, float* window_z, std::uint32_t* bits) {
  const simd::SnapConstants constants{c.guard_x, c.guard_y,     c.scale_x,
                                      c.scale_y, c.translate_x, c.translate_y};
  simd::window_vertices(constants, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
}

constexpr raster::SnapKernels kSimdSnapKernels{window_pass, simd::snap_vertices};

}  // namespace

const raster::SnapKernels& simd_snap_kernels() {
  return kSimdSnapKernels;
}

}  // namespace relief
