// The commands behind the CLI, each taking an already validated scene.
#pragma once

#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"
#include "tools/float_image_file.h"
#include "tools/image_compare.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

struct StagesOptions {
  std::string out_dir;                         // empty: scene.output.stages_dir
  FloatFormat raw_format = FloatFormat::kPfm;  // of the float files, NAME.pfm or NAME.exr
  int repeat = 1;
  Backend backend = Backend::kSimd;
  MemoryBudget budget;
};

// What loading the scene's resources noted (SceneResources::notes: a basis image that does not
// tile, a field basis mode ignores), each line once as "relief: note: ...".
void print_scene_notes(const std::vector<std::string>& notes, std::ostream& err);

// Each command checks its memory estimate (job_memory.h) against options.budget before it
// starts, and throws MemoryLimitError when the job does not fit.

// `relief stages`: stages 1-4, stage times (median over `repeat` runs), stage outputs.
int run_stages_command(const Scene& scene, const StagesOptions& options, std::ostream& out,
                       std::ostream& err);

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
  std::string shard;       // --shard I/N (tools/shard.h); empty: the whole image
};

// Refuses (returns kExitBadInput with the message on `err`, 0 otherwise) output names of the
// wrong kind and any output naming the same file as another output or an input of the scene
// (the scene file `scene_arg`, textures, sketch, basis images).
int check_render_paths(const Scene& scene, const std::string& scene_arg,
                       const RenderOptions& options, std::ostream& err);

// `relief render`: the whole frame to an sRGB PNG, with the stage times.
int run_render_command(const Scene& scene, const RenderOptions& options, std::ostream& out,
                       std::ostream& err);

struct RasterOptions {
  std::string soup;    // triangle soup file (docs/rasteriser.md, "Triangle soups")
  std::string prefix;  // output files PREFIX.*
  std::string cull = "none";
  std::string front_face = "ccw";
  std::string depth_test = "greater";
  std::vector<double> viewport;  // x y width height; empty: the framebuffer
  bool simd = true;              // the tiles through the SIMD kernels (the same bytes)
  MemoryBudget budget;
};

// The command and its own options (--backend, --threads, --max-memory: cli.cc).
CLI::App* add_raster_command(CLI::App& app, RasterOptions& options);

// `relief raster`: a triangle soup through the rasteriser, buffers written for comparison.
// Throws SoupError for a bad soup (soup.h).
int run_raster_command(const RasterOptions& options, std::ostream& out);

// `relief info`: the version, the build and the SIMD targets (pipeline/build_info.h).
int run_info_command(std::ostream& out);

struct CompareOptions {
  std::string a, b;  // the image files
  CompareThresholds thresholds;
  std::string diff;  // heat map PNG (empty: none)
  std::string json;  // the report as JSON (empty: none)
};

// `relief compare A B`: idiff's comparison (image_compare.h). Returns idiff's exit codes: 0
// pass, 1 warning, 2 failure, 3 different sizes, 4 anything that is not a comparison (a file
// that cannot be read, images with different channel counts, an output that cannot be
// written), with the message on `err`.
int run_compare_command(const CompareOptions& options, std::ostream& out, std::ostream& err);

// Adds the command and its options to `app` (compare_command.cc, beside what they fill).
CLI::App* add_compare_command(CLI::App& app, CompareOptions& options);
// idiff's six thresholds (--fail, --failpercent, --hardfail, --warn, --warnpercent,
// --hardwarn) as options of `command`.
void add_compare_thresholds(CLI::App* command, CompareThresholds& thresholds);

struct CrosscheckOptions {
  std::string out_dir;                   // the images, heat maps, table and JSON
  Backend cpu_backend = Backend::kSimd;  // the CPU side: simd or reference
  int repeat = 1;                        // frames per backend for the times (median)
  // idiff's, on the sRGB images as values / 255, over the pixels both frames give the same
  // triangle (crosscheck.h). Defaults: a pixel more than one code apart fails, one code apart
  // warns (docs/gl-shading.md: the paths may differ by one code).
  CompareThresholds thresholds{1.5f / 255, 0, std::numeric_limits<float>::infinity(),
                               0.5f / 255, 0, std::numeric_limits<float>::infinity()};
  bool all_pixels = false;  // judge every pixel, as idiff judges the two PNG files
  MemoryBudget budget;
  std::string cpu_backend_name = "simd";    // --cpu-backend as given
  std::string scene_arg;                    // SCENE as given: a file is an input
  const CLI::Option* out_option = nullptr;  // to tell --out "" from no --out
};

// Adds the command and its own options (SCENE, --set, --threads and --max-memory: cli.cc).
CLI::App* add_crosscheck_command(CLI::App& app, CrosscheckOptions& options);

// relief crosscheck's exit codes beyond idiff's verdicts (0 pass, 1 warning, 2 failure, 3 size
// mismatch): bad input or no GL is 4, as relief compare's; an output that cannot be written 5,
// so that a script tells each apart from a verdict.
inline constexpr int kCrosscheckBadInput = 4;
inline constexpr int kCrosscheckOutputError = 5;

// `relief crosscheck`: the scene by the CPU backend and by the GL backend, compared stage by
// stage (crosscheck.h). Returns idiff's exit code for the final images (0 pass, 1 warning,
// 2 failure, 3 size mismatch), 2 also where a pixel changed triangle away from any triangle
// boundary. Throws GlBackendError when there is no GL, OutputError when a file cannot be
// written.
int run_crosscheck_command(const Scene& scene, const CrosscheckOptions& options, std::ostream& out,
                           std::ostream& err);

struct StressOptions {
  std::vector<int> viewport = {640, 512};  // the base scene's size for the cases
  int grid_side = 256;
  std::vector<std::string> backends;  // empty: every backend of this build
  std::vector<std::string> axes;      // empty: every axis (stress_cases.h)
  std::string max_memory = "1G";      // the budget of the largest cases
  std::string sheet;                  // PNG of one thumbnail per case (empty: none)
};

// `relief stress`: the stability stress suite (eval/stress_run.h) on the scene, as a table.
// Returns 0 when every check holds, 1 when one does not.
int run_stress_command(const Scene& scene, const StressOptions& options, std::ostream& out,
                       std::ostream& err);

// Adds the command and its own options to `app` (stress_command.cc).
CLI::App* add_stress_command(CLI::App& app, StressOptions& options);

}  // namespace relief
