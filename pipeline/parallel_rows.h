// The frame plan's parallel loop (core/projector.h, ParallelRows) on oneTBB's pool: the core
// knows no threads, the pipeline hands it this.
#pragma once

#include "core/projector.h"

namespace relief {

// One task per row of the projector's refinement, on the calling thread's arena (so a
// tbb::global_control limit or a task_arena bounds it like every stage).
ParallelRows thread_pool_rows();

}  // namespace relief
