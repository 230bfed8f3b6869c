// Stage 2: the projected domain (§4.1, steps 1-2 and the LOD paragraph).
//
// For each grid vertex: the footprint of its projector ray on the base domain (camera-relative
// dx, dz), a validity flag, the local spacing sigma to its neighbours' footprints, and the
// octave count nu. Rays are recomputed for the four neighbours instead of read back, so any
// row range is independent of every other (a unit of parallel work) and border vertices need
// no special case.
#pragma once

#include <span>

#include "core/grid_buffers.h"
#include "core/stage_params.h"

namespace relief {

// Writes rows [rows.begin, rows.end) of `out` (all pitch entries of each row; padding
// entries get dx = dz = sigma = 0, nu = 1, valid = 0).
//   sigma: half the distance between the footprints of the two neighbours along a grid axis,
//          the larger of the two axes; one-sided where a neighbour is invalid.
//   nu:    clamp(c0 - c1 log2(sigma^2), 1, N) (frame_plan.h); N where sigma^2 is below
//          kMinSpacingSq, the log's domain guard.
// Invalid vertices (ray at or above the horizon, or beyond the farthest footprint) get
// dx = dz = sigma = 0 and nu = 1: finite, and skipped by every later stage.
// Vertex (i, j) is the image point (x0_j + i step_x_j, y0 + j step_y), x0_j and step_x_j its
// row's (screen_grid.h). `rows_table`: make_domain_rows() of the same plan.
template <class Real>
void project_domain(const DomainParams<Real>& params, const DomainRows<Real>& rows_table,
                    RowRange rows, DomainSpans<Real> out);

}  // namespace relief
