// `relief sweep [SCENE] --out DIR` (sweep_command.cc): the scene's frame time against its error
// for every knob of the real-time path (eval/sweep.h; docs/sweep.md).
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

struct SweepOptions {
  std::string out_dir;           // reference.exr, reference.png, sweep.csv, sweep.gp, sweep.png
  std::string reference;         // a reference to reuse (EXR or PFM, linear); empty: render it
  GroundTruthSettings settings;  // of the reference when it is rendered
  int repeat = 5;                // frames per configuration; the median time is reported
  bool quick = false;            // a small subset of the configurations (sweep_plan.h)
  MemoryBudget budget;
  const CLI::Option* out_option = nullptr;  // to tell --out "" from no --out
  const CLI::Option* reference_option = nullptr;
};

// Adds the command and its own options (SCENE, --set, --threads and --max-memory: cli.cc).
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);

// Returns an exit code: 0 (also when gnuplot is missing: the plot is left out with a warning),
// 2 for bad options (nothing written), 1 when an output cannot be written or gnuplot failed.
// Throws MemoryLimitError when the job does not fit options.budget, OutputError when a file
// cannot be written, GlBackendError when the GL backend fails mid-sweep.
int run_sweep_command(const Scene& scene, const SweepOptions& options, std::ostream& out,
                      std::ostream& err);

}  // namespace relief
