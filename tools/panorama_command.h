// `relief panorama [SCENE] -o OUT.png --width W` (panorama_command.cc, panorama.h): the scene
// seen all around from its camera, an equirectangular image resampled from a cube of six views,
// with its seams measured.
#pragma once

#include <iosfwd>
#include <string>

#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

struct PanoramaOptions {
  std::string output;  // .png
  int width = 2048;    // the equirectangular image's width; its height is half
  std::string json;    // the seams' figures; empty: none
  const CLI::Option* json_option = nullptr;  // to tell --json '' from no --json
  std::string scene_arg;                     // SCENE as given: a file is an input
  Backend backend = Backend::kSimd;
  MemoryBudget budget;
};

inline constexpr int kMinPanoramaWidth = 16;
inline constexpr int kMaxPanoramaWidth = 8192;

// Adds the command and its own options (SCENE, --set, --threads, --max-memory, --backend:
// cli.cc).
CLI::App* add_panorama_command(CLI::App& app, PanoramaOptions& options);

// Returns an exit code: 0, or 2 for bad options (nothing written). Throws MemoryLimitError when
// the six views and the image do not fit options.budget, OutputError when a file cannot be
// written.
int run_panorama_command(const Scene& scene, const PanoramaOptions& options, std::ostream& out,
                         std::ostream& err);

}  // namespace relief
