// The commands behind the CLI, each taking an already validated scene.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"

namespace relief {

struct StagesOptions {
  std::string out_dir;  // empty: scene.output.stages_dir
  int repeat = 1;
  Backend backend = Backend::kSimd;
  MemoryBudget budget;
};

// Each command checks its memory estimate (job_memory.h) against options.budget before it
// starts, and throws MemoryLimitError when the job does not fit.

// `relief stages`: stages 1-4, stage times (median over `repeat` runs), stage outputs.
int run_stages_command(const Scene& scene, const StagesOptions& options, std::ostream& out);

struct RenderOptions {
  std::string output;        // empty: scene.output.image
  std::string float_output;  // empty: scene.output.float_image (or none)
  // Extra per-pixel outputs (pipeline/frame.h), each written only when named.
  std::string depth_output, primitive_output, normal_output, height_output, octaves_output;
  int repeat = 1;
  Backend backend = Backend::kSimd;
  MemoryBudget budget;
  bool stats = false;      // per stage: ran or skipped, time, work counters
  std::string stats_json;  // the same as a JSON file (empty: none)
};

// `relief render`: the whole frame to an sRGB PNG, with the stage times.
int run_render_command(const Scene& scene, const RenderOptions& options, std::ostream& out);

struct RasterOptions {
  std::string soup;    // triangle soup file (README.md, "Triangle soups")
  std::string prefix;  // output files PREFIX.*
  std::string cull = "none";
  std::string front_face = "ccw";
  std::string depth_test = "greater";
  std::vector<double> viewport;  // x y width height; empty: the framebuffer
  bool simd = true;              // the tiles through the SIMD kernels (the same bytes)
  MemoryBudget budget;
};

// `relief raster`: a triangle soup through the rasteriser, buffers written for comparison.
// Throws SoupError for a bad soup (soup.h).
int run_raster_command(const RasterOptions& options, std::ostream& out);

// `relief info`: the version, the build and the SIMD targets (pipeline/build_info.h).
int run_info_command(std::ostream& out);

}  // namespace relief
