// The Highway half of the kernel table (cpu_kernels.h): the simd backend's kernels of simd/,
// float only, each the same bytes as its portable twin on every target (tests/simd/). An entry
// without a Highway kernel keeps the portable one and states why.
#include "pipeline/cpu_kernels.h"
#include "pipeline/simd_setup.h"
#include "simd/fbm.h"
#include "simd/planet_bend.h"
#include "simd/projected_domain.h"
#include "simd/sketch.h"
#include "simd/surface.h"
#include "simd/vertex_outcodes.h"
#include "simd/vertex_transform.h"

namespace relief {

namespace {

// The reasons, one per entry that stays portable on the simd backend.
constexpr const char* kSetupReason =
    "per-triangle clipping and edge set-up branch on each triangle; its vertices' snap is the "
    "vectorised part";
constexpr const char* kBinningReason =
    "integer bounding boxes appended to per-chunk bins: memory-bound, no Highway kernel";
constexpr const char* kHullSweepReason =
    "a stack per line of the cache whose pushes and pops depend on the heights "
    "(core/horizon_lines.h)";
constexpr const char* kReflectionMarchReason =
    "each ray's steps, jumps and end depend on the heights it passes (core/water_reflection.h); "
    "its set-up is the vectorised part";

}  // namespace

CpuKernels<float> highway_kernels(bool planet) {
  CpuKernels<float> k = portable_kernels<float>(planet);
  k.project_domain = &simd::project_domain;
  k.project_planet_domain = &simd::project_planet_domain;
  k.vertex_outcodes = &simd::vertex_outcodes;
  k.fractal = &simd::evaluate_fbm;
  k.sketch = &simd::add_sketch;
  k.bend_vertices = &simd::bend_vertices;
  k.bend_normals = &simd::bend_normals;
  k.surface = &simd::surface_pass;
  k.transform = &simd::transform_vertices;
  k.light_vertices = &simd::light_vertices;
  k.snap = &simd_snap_kernels();
  const KernelKind h = KernelKind::kHighway;
  k.tiles.raster = h;
  k.tiles.encode = h;
  k.tiles.resolve = h;
  k.tiles.shade = h;
  k.tiles.sun = h;  // no shadows or sky light on a planet (its table has no entry)
  k.tiles.sky = h;
  k.tiles.reflect = h;
  for (KernelChoice& c : k.choices) {
    const std::string_view name = c.kernel;
    if (name == "clip and edge set-up") {
      c.reason = kSetupReason;
    } else if (name == "binning") {
      c.reason = kBinningReason;
    } else if (name == "hull sweep") {
      c.reason = kHullSweepReason;
    } else if (name == "reflected rays' march") {
      c.reason = kReflectionMarchReason;

    } else {
      c.kind = h;
    }
  }
  return k;
}

}  // namespace relief
