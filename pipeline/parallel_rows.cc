#include "pipeline/parallel_rows.h"

#include <functional>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace relief {

ParallelRows thread_pool_rows() {
  return [](int count, const std::function<void(int)>& body) {
    // Isolated: while it waits, this thread runs no task from outside the loop, so a caller
    // holding a lock (the GL backend holds its context's) never meets itself in a task that
    // takes the same lock.
    tbb::this_task_arena::isolate(
        [&] { tbb::parallel_for(0, count, [&](int row) { body(row); }); });
  };
}

}  // namespace relief
