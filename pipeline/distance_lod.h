// The ground truth's octave count (frame.h, DistanceLod; docs/ground-truth.md) applied after
// stage 2 to a range of grid rows.
#pragma once

#include "core/grid_buffers.h"
#include "pipeline/frame.h"

namespace relief {

// For every valid vertex of `rows`: nu = clamp(c0 - c1 log2(dx^2 + dz^2 + gap_sq), 1, nu_max),
// computed in double whatever Real is, replacing stage 2's nu.
template <class Real>
void apply_distance_lod(const DistanceLod& lod, RowRange rows, GridBuffers<Real>& grid);

}  // namespace relief
