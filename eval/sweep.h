// relief sweep (docs/sweep.md): each configuration of a plan (sweep_plan.h) rendered, timed and
// measured against the ground truth (ground_truth.h), and the Pareto front of frame time
// against perceptual error (pareto.h).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "core/scene/scene.h"
#include "eval/sweep_plan.h"
#include "pipeline/memory_budget.h"

namespace relief {

struct SweepRow {
  SweepConfiguration configuration;
  double median_ms = 0;  // frame time (with the box filter, if any), median over the rounds
  // Against the reference, on display values (image_error.h).
  double psnr_db = 0, rmse = 0, max_error = 0, mean_flip = 0;
  // Stage 3's float heights against double at the same domain points (height_error.h), world
  // units; 0 for reference-double, whose heights are the double ones.
  double height_max = 0, height_rms = 0;
  bool on_pareto_front = false;  // of (median_ms, mean_flip) over the rows
};

// Called before each frame with (frames done, frames in all, what the next one is), and once at
// the end with an empty text.
using SweepProgress = std::function<void(int, int, std::string_view)>;

// Renders every configuration of a validated scene `repeat` (>= 1) times with the linear
// radiance, in rounds (each round renders every configuration once; one untimed frame first),
// reduces supersampled frames to the viewport (box_filter.h), and measures the first round's
// frame against `reference` (linear RGB of the scene's viewport, rows bottom to top). Marks
// the Pareto front. Throws SceneError (a configuration the scene refuses: plan_sweep skips those),
// MemoryLimitError (bins beyond max_bin_bytes), GlBackendError.
std::vector<SweepRow> run_sweep(const Scene& scene,
                                std::span<const SweepConfiguration> configurations,
                                std::span<const float> reference, int repeat,
                                std::uint64_t max_bin_bytes = UINT64_MAX,
                                const SweepProgress& progress = {});

// Peak memory of run_sweep beside the reference: the largest configuration's render with its
// linear radiance, its box-filtered copy and the error figures, or its height check.
MemoryEstimate sweep_memory(const Scene& scene, std::span<const SweepConfiguration> configurations);

}  // namespace relief
