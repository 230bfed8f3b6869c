#include "pipeline/parallel_rows.h"

#include <functional>

#include <tbb/parallel_for.h>

namespace relief {

ParallelRows thread_pool_rows() {
  return [](int count, const std::function<void(int)>& body) {
    tbb::parallel_for(0, count, [&](int row) { body(row); });
  };
}

}  // namespace relief
