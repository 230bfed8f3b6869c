// The simd backend's kernels for raster's triangle set-up (raster::SnapKernels), connected to
// the Highway kernels of simd/vertex_snap.h: raster and simd know nothing of each other.
#pragma once

#include "raster/triangle_setup.h"

namespace relief {

const raster::SnapKernels& simd_snap_kernels();

}  // namespace relief
