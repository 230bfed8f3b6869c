// The CPU backend's kernel table: for every stage of the frame (stage_table.h) that has more
// than one CPU implementation, the function this frame runs. The table is chosen once per frame
// (cpu_kernels) from the backend and the scene's kind, and every entry that is not the
// backend's own kind of kernel says why (KernelChoice::reason), so that `--stats` and
// `relief info` report each fallback instead of running it silently.
//
// The kinds: the portable loops of core/ and raster/ in float (the reference backend) or
// double (reference-double), and the Highway kernels of simd/ (the simd backend, float only,
// the same bytes as the portable float loops). The GL backend is its own FrameBackend
// (gl_backend.h) with its own table (gpu/).
//
// Adding a kernel: a pointer here, its portable entry in cpu_kernels_portable.cc, its Highway
// entry (or a stated reason) in cpu_kernels_highway.cc, and its call in cpu_backend.cc.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/fbm.h"
#include "core/grid_buffers.h"
#include "core/stage_params.h"
#include "core/surface.h"
#include "core/vertex_culling.h"
#include "core/vertex_transform.h"
#include "pipeline/frame.h"
#include "pipeline/kernel_kind.h"
#include "pipeline/stage_table.h"
#include "raster/triangle_setup.h"

namespace relief {

// One row of the table as reported: which stage, which of its kernels, which kind runs and,
// where a backend runs another kind than its own, why.
struct KernelChoice {
  StageId stage;
  const char* kernel;  // "vertex outcodes", "tile resolve", ...
  KernelKind kind;
  const char* reason;  // empty for the backend's own kind
};

template <class Real>
struct CpuKernels {
  // Stage 2 on the plane (core/projected_domain.h).
  void (*project_domain)(const DomainParams<Real>&, const DomainRows<Real>&, RowRange,
                         DomainSpans<Real>) = nullptr;
  // Stage 2 on a planet (core/planet_domain.h).
  void (*project_planet_domain)(const DomainParams<Real>&, const PlanetParams<Real>&,
                                const DomainRows<Real>&, RowRange, DomainSpans<Real>) = nullptr;
  // Which frustum planes each vertex (or its height range) lies outside (vertex_culling.h).
  void (*vertex_outcodes)(const CullParams<Real>&, RowRange, std::span<const Real> x,
                          std::span<const Real> z, std::span<const Real> height,
                          std::span<const std::uint8_t> valid,
                          std::span<std::uint8_t> outcode) = nullptr;
  // Stage 3: the fBm (core/fbm.h), then §3's sketch (core/height_sketch.h).
  FbmWork (*fractal)(const FbmParams<Real>&, const NoiseLattice&, IndexRange,
                     std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                     std::span<const std::uint8_t> mask, std::span<Real> height) = nullptr;
  void (*sketch)(const SketchParams<Real>&, std::span<const float> heights, IndexRange,
                 std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                 std::span<const std::uint8_t> mask, std::span<Real> height) = nullptr;
  // A planet's bend after stage 3, and its normals' rotation after stage 4 (core/planet_bend.h).
  void (*bend_vertices)(const PlanetParams<Real>&, IndexRange, std::span<const Real> dx,
                        std::span<const Real> dz, std::span<const Real> height,
                        std::span<const std::uint8_t> valid, BentSpans<Real>) = nullptr;
  void (*bend_normals)(const PlanetParams<Real>&, IndexRange, std::span<const Real> dx,
                       std::span<const Real> dz, std::span<const std::uint8_t> valid,
                       std::span<Real> nx, std::span<Real> ny, std::span<Real> nz) = nullptr;
  // Stage 4 (core/surface.h).
  void (*surface)(const SurfaceParams<Real>&, RowRange, SurfaceInputs<Real>,
                  SurfaceSpans<Real>) = nullptr;
  // Stage 5 (core/vertex_transform.h).
  void (*transform)(const TransformParams<Real>&, IndexRange, std::span<const Real> dx,
                    std::span<const Real> dz, std::span<const Real> height,
                    std::span<const std::uint8_t> need, ClipSpans<Real>) = nullptr;
  // Stage 5's Gouraud lighting in gradient mode (core/vertex_transform.h).
  void (*light_vertices)(const TransformParams<Real>&, IndexRange, std::span<const Real> nx,
                         std::span<const Real> ny, std::span<const Real> nz,
                         std::span<const std::uint8_t> need, std::span<Real> lambert) = nullptr;
  // Stage 6's vertex snap (raster/triangle_setup.h); null: raster's portable loops.
  const raster::SnapKernels* snap = nullptr;
  // Stages 6-9 per tile.
  TileKernels tiles;
  // Every kernel of the frame, the ones above and those with one kind only (set-up, binning),
  // in stage order, as `--stats` and `relief info` print them.
  std::vector<KernelChoice> choices;
};

// The table of a frame of `backend` (kReference, kReferenceDouble or kSimd; Real double only
// with kReferenceDouble) on a plane or a planet (docs/planet.md).
template <class Real>
CpuKernels<Real> cpu_kernels(Backend backend, bool planet);

// The two halves of it, one file each: every entry portable, with `reason` for each (empty for
// the reference backends, whose own kind it is); and the Highway table of the simd backend.
template <class Real>
CpuKernels<Real> portable_kernels(bool planet);
CpuKernels<float> highway_kernels(bool planet);

// "Highway (AVX3)" or "portable loop (float)": a kind as the reports name it.
std::string kernel_kind_label(KernelKind kind, bool double_precision);

// The table as `--stats` and `relief info` print it: one line per kernel,
// "STAGE / KERNEL: KIND[, because REASON]".
std::vector<KernelReport> kernel_reports(std::span<const KernelChoice> choices,
                                         bool double_precision);

}  // namespace relief
