// The commands behind the CLI, each taking an already validated scene.
#pragma once

#include <iosfwd>
#include <string>

#include "core/scene.h"

namespace relief {

struct StagesOptions {
  std::string out_dir;  // empty: scene.output.stages_dir
  int repeat = 1;
};

// `relief stages`: stages 1-4, stage times (median over `repeat` runs), stage outputs.
int run_stages_command(const Scene& scene, const StagesOptions& options, std::ostream& out);

}  // namespace relief
