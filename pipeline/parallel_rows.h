// The frame plan's parallel loop (core/projector.h, ParallelRows) on oneTBB's pool: the core
// knows no threads, the pipeline hands it this.
#pragma once

#include "core/projector.h"

namespace relief {

// The projector's refinement's rows as a tbb::parallel_for (its partitioner groups them into
// tasks) on the calling thread's arena, isolated (a thread waiting in it takes no outside
// task), so a tbb::global_control limit or a task_arena bounds it like every stage.
ParallelRows thread_pool_rows();

}  // namespace relief
