// Runs the terrain stages of a frame on all cores: each stage is a tbb::parallel_for over
// fixed chunks of grid rows, and a stage starts when the previous one has finished every row
// (stage 4 reads neighbouring rows). Every row's values are a pure function of the plan, so
// the buffers are bit-identical for any thread count.
#pragma once

#include "core/frame_plan.h"
#include "core/grid_buffers.h"

namespace relief {

struct StageTimings {
  double projected_domain_ms = 0;  // stages 1-2
  double fbm_ms = 0;               // stage 3
  double surface_ms = 0;           // stage 4
};

template <class Real>
StageTimings run_terrain_stages_parallel(const FramePlan& plan, GridBuffers<Real>& buffers);

}  // namespace relief
