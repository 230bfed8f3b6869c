// Runs the terrain stages of a frame on all cores: each stage is a tbb::parallel_for over
// fixed chunks of grid rows, and a stage starts when the previous one has finished every row
// (stage 4 reads neighbouring rows). Every row's values are a pure function of the plan, so
// the buffers are bit-identical for any thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"

namespace relief {

// body(RowRange) over [0, rows) in fixed chunks of rows_per_task rows (simple_partitioner: the
// chunks never depend on the thread count), so a stage whose rows are pure functions of its
// inputs gives the same bits on any number of threads. Every parallel stage of a frame runs
// through this.
template <class Body>
void parallel_rows(int rows, int rows_per_task, Body body) {
  tbb::parallel_for(
      tbb::blocked_range<int>(0, rows, rows_per_task),
      [&](const tbb::blocked_range<int>& r) {
        body(RowRange{r.begin(), r.end()});
      },
      tbb::simple_partitioner());
}

struct StageTimings {
  double projected_domain_ms = 0;  // stages 1-2
  double fbm_ms = 0;               // stage 3
  double surface_ms = 0;           // stage 4
};

template <class Real>
StageTimings run_terrain_stages_parallel(const FramePlan& plan, GridBuffers<Real>& buffers);

}  // namespace relief
