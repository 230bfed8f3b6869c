// The core's one way to run independent rows of work at once: the core knows no threads, so a
// caller that has a thread pool hands in its loop (pipeline/parallel_rows.h: oneTBB's), and an
// empty one is a plain loop (run_rows).
#pragma once

#include <functional>

namespace relief {

// Runs body(0) ... body(count - 1), each exactly once, in any order and possibly at once; each
// call writes only its own outputs. The result never depends on the order.
using ParallelRows = std::function<void(int count, const std::function<void(int)>& body)>;

// `parallel` when it is set, else the rows in order on this thread.
inline void run_rows(const ParallelRows& parallel, int count,
                     const std::function<void(int)>& body) {
  if (parallel) {
    parallel(count, body);
    return;
  }
  for (int row = 0; row < count; ++row) {
    body(row);
  }
}

}  // namespace relief
