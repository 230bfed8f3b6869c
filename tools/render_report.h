// What `relief render` reports about its frames (docs/stages.md, "Skipped work"): the median
// stage times of the runs, and with --stats each stage's ran-or-skipped, time and work counters,
// as text or as JSON for CI (--stats-json).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/scene.h"
#include "pipeline/frame.h"

namespace relief {

// The statistics of repeated renders of one scene: per run the stages and the fused stage's
// parts in the order they ran, and the frame's total; `last` the last run's (the counters are
// the same in every run).
struct RenderRuns {
  std::vector<std::vector<StageTime>> stages, parts, gpu_passes;
  std::vector<double> totals;
  FrameStats last;
  double setup_ms = 0;

  void add(const FrameStats& stats);
};

// One line per stage with its median time, the fused stage's parts, the frame.
void print_stage_times(std::ostream& out, const RenderRuns& runs);

// Per stage: ran or skipped, median time, and each work counter on its own line; a GL frame's
// passes (FrameStats::gpu_passes); then the kernel table (print_kernel_table).
void print_stage_stats(std::ostream& out, const RenderRuns& runs);

// A CPU frame's kernels, one line each: "STAGE / KERNEL: KIND[, because REASON]"; nothing for
// a GL frame.
void print_kernel_table(std::ostream& out, const std::vector<KernelReport>& kernels);

// The same as JSON: {"image", "grid", "backend", "runs", "frame_ms", "setup_ms", "stages":
// [{"name", "ran", "ms", "counters": {name: value}}], "tile_parts": [{"name", "ms"}],
// "gpu_passes": [{"name", "ms"}] (empty for the CPU backends),
// "kernels": [{"stage", "kernel", "implementation", "reason"}] (empty for GL), "raster": {...}}.
nlohmann::json stage_stats_json(const Scene& scene, Backend backend, const RenderRuns& runs);

}  // namespace relief
