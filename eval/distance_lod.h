// The ground truth's octave count (docs/ground-truth.md) applied after stage 2 to a range of
// grid rows: the rule a ground-truth frame installs in its FrameRequest (OctaveCountRule,
// pipeline/frame.h) in place of stage 2's LOD rule.
#pragma once

#include <memory>

#include "core/grid_buffers.h"
#include "pipeline/frame.h"

namespace relief {

// The octave count from a lower bound of each vertex's distance to the camera instead of the
// grid spacing: nu = clamp(c0 - c1 log2(dx^2 + dz^2 + gap_sq), 1, nu_max), nu_max where the
// squared distance is below limits::kMinSpacingSq (the log's domain guard).
struct DistanceLod {
  double c0 = 0, c1 = 0, nu_max = 1;
  double gap_sq = 0;  // squared height of the camera above the highest possible terrain, or 0
};

// For every valid vertex of `rows`: the rule above, computed in double whatever Real is,
// replacing stage 2's nu.
template <class Real>
void apply_distance_lod(const DistanceLod& lod, RowRange rows, GridBuffers<Real>& grid);

// `lod` as a FrameRequest's octave_count_rule.
std::shared_ptr<const OctaveCountRule> distance_lod_rule(const DistanceLod& lod);

}  // namespace relief
