// Stages 1-4 of a frame, in order, over a row range: the reference pipeline, single
// threaded. Parallel callers split the grid into row chunks and call the stage functions
// themselves (stage 4 reads one row beyond its range, so it runs after stage 3 has finished
// the neighbouring rows).
#pragma once

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/height_sketch.h"
#include "core/octave_coordinates.h"
#include "core/planet_bend.h"
#include "core/planet_domain.h"
#include "core/projected_domain.h"
#include "core/stage_params.h"
#include "core/surface.h"

namespace relief {

template <class Real>
SurfaceInputs<Real> surface_inputs(const GridBuffers<Real>& buffers,
                                   std::span<const std::uint8_t> need = {}) {
  return {buffers.dx, buffers.dz, buffers.height, buffers.valid, need};
}

// Stage 3 over whole rows [rows.begin, rows.end), where `mask` is non-zero (empty: all).
template <class Real>
FbmWork evaluate_fbm_rows(const FbmParams<Real>& params, const NoiseLattice& lattice, RowRange rows,
                          GridBuffers<Real>& buffers, std::span<const std::uint8_t> mask = {}) {
  const IndexRange range{buffers.layout.index(0, rows.begin), buffers.layout.index(0, rows.end)};
  return evaluate_fbm<Real>(params, lattice, range, buffers.dx, buffers.dz, buffers.nu, mask,
                            buffers.height);
}

// Stage 3's second part, §3's sketch, over whole rows where `mask` is non-zero (empty: all);
// nothing when the frame has none.
template <class Real>
void add_sketch_rows(const SketchParams<Real>& params, const HeightSketch* sketch, RowRange rows,
                     GridBuffers<Real>& buffers, std::span<const std::uint8_t> mask = {}) {
  if (params.enabled == 0 || sketch == nullptr) {
    return;
  }
  const IndexRange range{buffers.layout.index(0, rows.begin), buffers.layout.index(0, rows.end)};
  add_sketch<Real>(params, sketch->heights, range, buffers.dx, buffers.dz, buffers.nu, mask,
                   buffers.height);
}

// Stages 2, 3 and 4 over the whole grid, with parameters derived from `plan` for this call:
// every valid vertex, none culled (heights of invalid vertices 0, as the frame leaves them).
// A planet frame (docs/planet.md) runs stage 2 on the sphere, bends the vertices after stage 3
// (into the bent spans, allocated here) and rotates the normals after stage 4.
template <class Real>
void run_terrain_stages(const FramePlan& plan, GridBuffers<Real>& buffers) {
  TerrainParams<Real> params = make_terrain_params<Real>(plan);
  const RowRange all{0, buffers.layout.height};
  const bool planet = params.planet.enabled != 0;
  if (planet) {
    project_planet_domain<Real>(params.domain, params.planet, params.domain_rows, all,
                                buffers.domain());
  } else {
    project_domain<Real>(params.domain, params.domain_rows, all, buffers.domain());
  }
  choose_coordinate_forms(plan.terrain,
                          octave_reach<Real>(IndexRange{0, buffers.layout.size()}, buffers.dx,
                                             buffers.dz, buffers.nu, buffers.valid),
                          params.fbm);
  evaluate_fbm_rows<Real>(params.fbm, *plan.terrain.lattice, all, buffers, buffers.valid);
  add_sketch_rows<Real>(params.sketch, plan.terrain.sketch, all, buffers, buffers.valid);
  const IndexRange every{0, buffers.layout.size()};
  if (planet) {
    if (buffers.bent_x.size() != buffers.layout.size()) {
      buffers.allocate_bent();
    }
    bend_vertices<Real>(params.planet, every, buffers.dx, buffers.dz, buffers.height, buffers.valid,
                        buffers.bent());
  }
  surface_pass<Real>(params.surface, all, surface_inputs(buffers), buffers.surface());
  if (planet) {
    bend_normals<Real>(params.planet, every, buffers.dx, buffers.dz, buffers.valid, buffers.nx,
                       buffers.ny, buffers.nz);
  }
}

}  // namespace relief
