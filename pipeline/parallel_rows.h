// The core's parallel loop (core/parallel_rows.h, ParallelRows) on oneTBB's pool, for the frame
// plan's projector and a height field's GeoMipMap: the core knows no threads, the pipeline hands
// it this.
#pragma once

#include "core/parallel_rows.h"

namespace relief {

// The projector's refinement's rows as a tbb::parallel_for (its partitioner groups them into
// tasks) on the calling thread's arena, isolated (a thread waiting in it takes no outside
// task), so a tbb::global_control limit or a task_arena bounds it like every stage.
ParallelRows thread_pool_rows();

}  // namespace relief
