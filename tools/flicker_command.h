// `relief flicker [SCENE] --move forward|turn --step S --frames F` (eval/flicker.h;
// docs/ground-truth.md, "Flicker"): a short camera move in real time and as ground truth, the
// real-time frames' error against their truths and how much each sequence changes from frame to
// frame, per band of distance.
#pragma once

#include <iosfwd>
#include <string>

#include "core/scene/scene.h"
#include "eval/ground_truth.h"
#include "pipeline/memory_budget.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

inline constexpr int kMaxFlickerFrames = 64;

struct FlickerOptions {
  std::string move = "forward";
  double step = 4.0;  // world units (forward) or degrees (turn) a frame
  int frames = 5;
  GroundTruthSettings settings;
  std::string json;
  MemoryBudget budget;
  std::string scene_arg;  // SCENE as given: a file is an input --json may not name
  const CLI::Option* json_option = nullptr;
};

CLI::App* add_flicker_command(CLI::App& app, FlickerOptions& options);

// Returns an exit code; bad options on `err` (2, nothing written). Throws MemoryLimitError,
// OutputError.
int run_flicker_command(const Scene& scene, const FlickerOptions& options, std::ostream& out,
                        std::ostream& err);

}  // namespace relief
