// `relief path [SCENE] --frames N --from-altitude A --to-altitude B --out DIR`
// (path_command.cc): §4.1's viewer moving from orbit close to the surface, a radial descent of the
// scene's camera (docs/planet.md), written as
// DIR/frame_0000.png, ...: the altitude above terrain.base_height log-uniform from A to B, the
// pitch easing from the scene's (looking down at the planet) to --to-pitch (near-horizontal),
// through the equal-angle band of a planet scene.
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

struct PathOptions {
  std::string out_dir;
  int frames = 0;
  double from_altitude = 0, to_altitude = 0;
  double to_pitch_deg = -8.0;
  Backend backend = Backend::kSimd;
  MemoryBudget budget;
  // --shard I/N (tools/shard.h): frames [floor(I F / N), floor((I + 1) F / N)) alone, and the
  // record relief-shard-I-of-N.json beside them; empty: every frame.
  std::string shard;
};

// Adds the command and its own options (SCENE, --set, --threads, --max-memory, --backend:
// cli.cc).
CLI::App* add_path_command(CLI::App& app, PathOptions& options);

// The camera of frame k of n (0 <= k < n): x and z the scene's, y = base_height + altitude,
// pitch eased; exposed for the tests.
CameraSettings path_camera(const Scene& scene, const PathOptions& options, int k);

// Returns an exit code: 0, or 2 for bad options or a frame whose scene is invalid (nothing
// written). Each frame is written through a temporary file and renamed. Throws
// MemoryLimitError when a frame does not fit options.budget, OutputError when a file cannot
// be written.
int run_path_command(const Scene& scene, const PathOptions& options, std::ostream& out,
                     std::ostream& err);

}  // namespace relief
