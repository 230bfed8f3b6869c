// `relief reference` (reference_command.cc) and `relief error` (error_command.cc): the ground
// truth and the error of any render against it (docs/ground-truth.md).
#pragma once

#include <iosfwd>
#include <string>

#include "core/scene/scene.h"
#include "eval/flip.h"
#include "eval/ground_truth.h"
#include "pipeline/memory_budget.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

struct ReferenceOptions {
  std::string output = "reference.png";
  std::string float_output;  // empty: output with .exr for .png
  GroundTruthSettings settings;
  bool stats = false;  // stage times, and the float height error at the scene's grid
  MemoryBudget budget;
  std::string shard;      // --shard I/N (tools/shard.h); empty: the whole image
  bool converge = false;  // also render at twice the settings and report the difference
  std::string json;       // --json: the convergence figures (with --converge)
  std::string scene_arg;  // SCENE as given: a file is an input no output may name
  const CLI::Option* output_option = nullptr;  // to tell -o "" from no -o
  const CLI::Option* float_option = nullptr;
  const CLI::Option* json_option = nullptr;
};

// Adds the command and its own options (SCENE, --set, --threads and --max-memory: cli.cc).
CLI::App* add_reference_command(CLI::App& app, ReferenceOptions& options);

// Returns an exit code; bad options are reported on `err` (2, nothing written). Throws
// MemoryLimitError when the job does not fit options.budget, OutputError when a file cannot be
// written.
int run_reference_command(const Scene& scene, const ReferenceOptions& options, std::ostream& out,
                          std::ostream& err);

struct ErrorOptions {
  std::string test, reference;  // image files: PNG (sRGB), EXR or PFM (linear radiance)
  std::string map;              // FLIP heat map PNG (empty: none)
  std::string json;             // the figures as JSON (empty: none)
  double pixels_per_degree = kDefaultPixelsPerDegree;
  MemoryBudget budget;
};

CLI::App* add_error_command(CLI::App& app, ErrorOptions& options);

// Returns 0 with the figures printed, 2 for bad input (a file that is not a readable image,
// images of different sizes, too little memory; nothing written), 1 when an output cannot be
// written; messages on `err`.
int run_error_command(const ErrorOptions& options, std::ostream& out, std::ostream& err);

}  // namespace relief
