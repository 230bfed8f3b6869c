#include "pipeline/frame_runner.h"

#include <chrono>

#include "core/terrain_stages.h"

namespace relief {

namespace {

// Rows per task: 512-vertex rows make ~40 us of fBm work per row, so 4 rows amortise the
// scheduling cost while leaving 128 tasks to balance over the cores.
constexpr int kRowsPerTask = 4;

template <class Body>
double timed_parallel_rows(int rows, Body body) {
  const auto start = std::chrono::steady_clock::now();
  parallel_rows(rows, kRowsPerTask, body);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

template <class Real>
StageTimings run_terrain_stages_parallel(const FramePlan& plan, GridBuffers<Real>& buffers) {
  const int rows = buffers.layout.height;
  StageTimings timings;
  timings.projected_domain_ms = timed_parallel_rows(
      rows, [&](RowRange r) { project_domain<Real>(plan, r, buffers.domain()); });
  timings.fbm_ms =
      timed_parallel_rows(rows, [&](RowRange r) { evaluate_fbm_rows<Real>(plan, r, buffers); });
  timings.surface_ms = timed_parallel_rows(rows, [&](RowRange r) {
    surface_pass<Real>(plan, r, surface_inputs(buffers), buffers.surface());
  });
  return timings;
}

template StageTimings run_terrain_stages_parallel<float>(const FramePlan&, GridBuffers<float>&);
template StageTimings run_terrain_stages_parallel<double>(const FramePlan&, GridBuffers<double>&);

}  // namespace relief
