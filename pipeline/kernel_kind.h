// The kinds of kernel a CPU stage can run (cpu_kernels.h), and the kind of each part of the
// fused tile stage (tile_pass.h).
#pragma once

#include <cstdint>

namespace relief {

enum class KernelKind : std::uint8_t {
  kPortable,  // the loops of core/ and raster/, in the backend's precision
  kHighway,   // the Highway kernels of simd/ on the target simd::current_target() names
};

// Stages 6-9 per tile: each part's kind. Highway parts run only in float.
struct TileKernels {
  KernelKind raster = KernelKind::kPortable;
  KernelKind resolve = KernelKind::kPortable;
  KernelKind sun = KernelKind::kPortable;  // cast shadows' share of the sun (sun_visibility.h)
  KernelKind sky = KernelKind::kPortable;  // sky light's share of the sky (sky_horizons.h)
  // The reflected rays' set-up (water_reflection.h, simd/reflection_rays.h); their march is
  // portable in every backend.
  KernelKind reflect = KernelKind::kPortable;
  KernelKind shade = KernelKind::kPortable;
  KernelKind encode = KernelKind::kPortable;
};

}  // namespace relief
