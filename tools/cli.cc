#include "tools/cli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <new>
#include <ostream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/memory_budget.h"
#include "tools/atomic_file.h"
#include "tools/commands.h"
#include "tools/soup.h"

namespace relief {

namespace {

std::string preset_list() {
  std::string out;
  for (const std::string& name : preset_names()) {
    out += (out.empty() ? "" : ", ") + name;
  }
  return out;
}

// SCENE and --set, shared by every command that renders a scene.
struct SceneArgs {
  std::string scene;
  std::vector<std::string> overrides;
};

void add_scene_args(CLI::App* command, SceneArgs& args) {
  command->add_option("SCENE", args.scene,
                      "Scene: a JSON file, or a preset name (" + preset_list() +
                          "). Default: the built-in default scene.");
  command
      ->add_option("--set", args.overrides,
                   "Override one scene field, validated like the scene file; repeatable, "
                   "applied in order. Example: --set terrain.H=0.85 --set grid.width=256")
      ->type_name("KEY=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// Memory limit of a job (memory_budget.h): "2G", "512M", bytes.
void add_max_memory(CLI::App* command, std::string& max_memory) {
  command
      ->add_option("--max-memory", max_memory,
                   "Refuse the job (exit 2) if its estimated memory exceeds SIZE (for example "
                   "512M, 2G). Default: the memory available on this machine.")
      ->type_name("SIZE")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return parse_memory_size(text) ? ""
                                           : "a size from 1M to 1E: a number with an optional "
                                             "unit K, M, G or T (powers of 1024)";
          },
          "SIZE"));
}

// A finite coordinate within +-1e6 (CLI::Range lets NaN through: every comparison with it is
// false).
const CLI::Validator kFiniteViewportValue(
    [](std::string& text) -> std::string {
      double v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v) ||
          std::abs(v) > 1e6) {
        return "'" + brief_text(text) + "' is not a finite number in [-1e6, 1e6]";
      }
      return "";
    },
    "NUMBER in [-1e6, 1e6]");

// `name` ends in `extension` (lower case), in any letter case.
bool has_extension(const std::string& name, std::string_view extension) {
  if (name.size() < extension.size()) {
    return false;
  }
  for (std::size_t k = 0; k < extension.size(); ++k) {
    const char c = name[name.size() - extension.size() + k];
    if (std::tolower(static_cast<unsigned char>(c)) != extension[k]) {
      return false;
    }
  }
  return true;
}

// An option given with an empty value (-o ""): never silently the default.
bool given_empty(const CLI::Option* option, const std::string& value) {
  return option->count() > 0 && value.empty();
}

// --backend NAME (pipeline/frame.h): which implementation runs the frame's stages; --simd
// TARGET forces one Highway target (implies --backend simd).
void add_backend(CLI::App* command, std::string& backend, std::string& simd_target) {
  command->add_option("--simd", simd_target,
                      "Run the simd backend on this Highway target (AVX3, AVX2, SSE4, SSSE3, "
                      "SCALAR: relief info lists those compiled in and those this CPU runs); "
                      "every target gives the same bytes");
  std::string names;
  for (std::string_view name : backend_names()) {
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  command
      ->add_option("--backend", backend,
                   "Implementation of the stages: simd (the default: Highway kernels), "
                   "reference (the scalar float stages; simd gives their bytes exactly), "
                   "reference-double (every stage in double, for accuracy comparisons) or gl "
                   "(the GLSL twins on OpenGL 4.5: a GPU, or Mesa's llvmpipe)")
      ->check(CLI::Validator(
          [names](std::string& text) -> std::string {
            return backend_from_name(text) ? "" : "unknown backend; allowed: " + names;
          },
          "NAME"));
}

void add_threads(CLI::App* command, int& threads) {
  command
      ->add_option("--threads", threads,
                   "Worker threads (default: all cores). Results are bit-identical for any count.")
      ->check(CLI::Range(1, 1024));
}

}  // namespace

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "Relief renders procedural fractal landscapes (Schneider, Boldte & Westermann, VMV 2006) "
      "with a deterministic CPU pipeline.\n"
      "Scenes are JSON files or built-in presets; every field can be overridden with --set.\n"
      "The scene reference and the stage-by-stage map to the paper are in README.md.",
      "relief"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 bad input (nothing written), 1 output not written.\n"
      "Run 'relief COMMAND --help' for the options of one command.");

  SceneArgs scene_args;
  int threads = 0;

  CLI::App* scene_cmd =
      app.add_subcommand("scene",
                         "Print the effective scene (defaults, preset or file, then "
                         "--set overrides) as JSON.");
  add_scene_args(scene_cmd, scene_args);

  StagesOptions stages;
  CLI::App* stages_cmd = app.add_subcommand(
      "stages",
      "Run stages 1-4 (screen grid, projected domain, fractal, surface) and write "
      "each stage's buffers as PNG pictures and PFM floats, with stages.json.");
  add_scene_args(stages_cmd, scene_args);
  const CLI::Option* stages_out =
      stages_cmd->add_option("--out", stages.out_dir,
                             "Output directory (created if missing). Default: the scene's "
                             "output.stages_dir");
  stages_cmd
      ->add_option("--repeat", stages.repeat,
                   "Run the stages this many times and report the median stage times")
      ->check(CLI::Range(1, 1000));
  add_threads(stages_cmd, threads);
  std::string max_memory;
  add_max_memory(stages_cmd, max_memory);
  std::string backend = "simd";
  std::string simd_target;
  add_backend(stages_cmd, backend, simd_target);

  RenderOptions render;
  CLI::App* render_cmd =
      app.add_subcommand("render",
                         "Render the scene to an sRGB PNG (stages 1-9: projected grid, fractal, "
                         "surface, rasterisation, proto-texture shading, water, sky) and print the "
                         "stage times.");
  add_scene_args(render_cmd, scene_args);
  const CLI::Option* render_out =
      render_cmd->add_option("-o,--output", render.output,
                             "PNG file to write (default: the scene's output.image, relief.png)");
  const CLI::Option* render_float =
      render_cmd->add_option("--float", render.float_output,
                             "Also write the linear radiance as a PFM file (default: the "
                             "scene's output.float_image, if set)");
  // Extra per-pixel outputs of the fused back end, each written only when named.
  const std::vector<std::tuple<const char*, std::string*, const char*>> extra_outputs = {
      {"--depth", &render.depth_output, "window depth (reverse-Z) as a PFM file"},
      {"--primitive", &render.primitive_output,
       "winning triangle id per pixel, uint32 little-endian (4294967295: none)"},
      {"--normal", &render.normal_output, "unit normal as a 3-channel PFM file"},
      {"--height", &render.height_output, "world height of the terrain as a PFM file"},
      {"--octaves", &render.octaves_output, "octave count nu as a PFM file"}};
  std::vector<const CLI::Option*> extra_options;
  for (const auto& [name, target, what] : extra_outputs) {
    extra_options.push_back(render_cmd->add_option(
        name, *target, std::string("Also write the ") + what + ", rows bottom to top"));
  }
  render_cmd
      ->add_option("--repeat", render.repeat,
                   "Render this many times and report the median stage times")
      ->check(CLI::Range(1, 1000));
  add_threads(render_cmd, threads);
  add_max_memory(render_cmd, max_memory);
  add_backend(render_cmd, backend, simd_target);
  render_cmd->add_flag("--stats", render.stats,
                       "Print per stage whether it ran or was skipped, its median time and its "
                       "work counters (vertices evaluated, triangles set up, texture fetches...)");
  const CLI::Option* render_stats_json = render_cmd->add_option(
      "--stats-json", render.stats_json, "Also write the --stats report as a JSON file, for CI");

  RasterOptions raster_options;
  CLI::App* raster_cmd = app.add_subcommand(
      "raster",
      "Rasterise a triangle soup (README.md, 'Triangle soups') and write the primitive "
      "id, depth and barycentric buffers, for comparison with a GPU.");
  raster_cmd->add_option("FILE", raster_options.soup, "Triangle soup text file")->required();
  const CLI::Option* raster_out = raster_cmd
                                      ->add_option("--out", raster_options.prefix,
                                                   "Output prefix: writes PREFIX.primitive.bin, "
                                                   "PREFIX.depth.pfm, PREFIX.barycentric.pfm, "
                                                   "PREFIX.coverage.png, PREFIX.json")
                                      ->required();
  raster_cmd->add_option("--cull", raster_options.cull, "Face culling: none (default), back, front")
      ->check(CLI::IsMember({"none", "back", "front"}));
  raster_cmd
      ->add_option("--front-face", raster_options.front_face,
                   "Front-facing winding in GL window coordinates: ccw (default) or cw")
      ->check(CLI::IsMember({"ccw", "cw"}));
  raster_cmd
      ->add_option("--depth-test", raster_options.depth_test,
                   "Depth test: greater (default, reverse-Z; depth cleared to 0), gequal, "
                   "less, lequal (cleared to 1), equal, always, never")
      ->check(CLI::IsMember({"greater", "gequal", "less", "lequal", "equal", "always", "never"}));
  raster_cmd
      ->add_option("--viewport", raster_options.viewport,
                   "glViewport X Y WIDTH HEIGHT for clip-coordinate soups (default: the "
                   "framebuffer); may exceed the framebuffer")
      ->expected(4)
      ->check(kFiniteViewportValue);
  add_backend(raster_cmd, backend, simd_target);
  add_threads(raster_cmd, threads);
  add_max_memory(raster_cmd, max_memory);

  CLI::App* info_cmd = app.add_subcommand(
      "info",
      "Print the version, how this build was compiled and its SIMD targets: those "
      "compiled in, those this CPU runs, and the one the simd backend uses.");

  // CLI11 answers an unknown command with "A subcommand is required"; say what is wrong.
  const std::vector<std::string> commands = {"scene", "stages", "render", "raster", "info"};
  if (args.size() > 1 && !args[1].empty() && args[1][0] != '-' &&
      std::find(commands.begin(), commands.end(), args[1]) == commands.end()) {
    err << "relief: error: unknown command '" << brief_text(args[1])
        << "'; commands: scene, stages, render, raster, info\nRun 'relief --help' for "
           "usage.\n";
    return kExitBadInput;
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) {
    argv.push_back(a.c_str());
  }
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    err << "relief: error: " << brief_text(e.what(), 3 * kBriefChars)
        << "\nRun 'relief --help' for usage.\n";
    return kExitBadInput;
  }
  std::vector<std::pair<const CLI::Option*, std::string>> named = {
      {stages_out, stages.out_dir},
      {render_out, render.output},
      {render_float, render.float_output},
      {render_stats_json, render.stats_json},
      {raster_out, raster_options.prefix}};
  for (std::size_t k = 0; k < extra_options.size(); ++k) {
    named.emplace_back(extra_options[k], *std::get<1>(extra_outputs[k]));
  }
  for (const auto& [option, value] : named) {
    if (given_empty(option, value)) {
      err << "relief: error: " << option->get_name()
          << " is empty; give a file or directory name\n";
      return kExitBadInput;
    }
  }
  if (raster_cmd->parsed() && raster_options.soup.empty()) {
    err << "relief: error: FILE is empty; give the triangle soup's file name\n";
    return kExitBadInput;
  }
  for (CLI::App* command : {scene_cmd, stages_cmd, render_cmd}) {
    if (command->parsed() && given_empty(command->get_option("SCENE"), scene_args.scene)) {
      err << "relief: error: SCENE is empty; give a scene file or a preset name, or leave it "
             "out for the default scene\n";
      return kExitBadInput;
    }
  }
  if (raster_cmd->parsed()) {
    // PREFIX names files: "out/" or "." would write hidden files named ".json", "..json".
    const std::string file = std::filesystem::path(raster_options.prefix).filename().string();
    if (file.empty() || file == "." || file == "..") {
      err << "relief: error: --out " << brief_text(raster_options.prefix)
          << " has no file name part; give a prefix such as out/soup\n";
      return kExitBadInput;
    }
  }
  const MemoryBudget budget = memory_budget(parse_memory_size(max_memory), max_memory);
  stages.budget = render.budget = raster_options.budget = budget;
  if (info_cmd->parsed()) {
    return run_info_command(out);
  }
  // The forced target is the process's: undone when this command returns, so that a caller
  // running several commands in one process (the tests) gets the best target afterwards.
  bool simd_forced = false;
  const auto unforce = [](bool* forced) {
    if (*forced) {
      force_simd_target("best");
    }
  };
  const std::unique_ptr<bool, decltype(unforce)> restore_target(&simd_forced, unforce);
  if (!simd_target.empty()) {
    CLI::App* command = stages_cmd->parsed()   ? stages_cmd
                        : raster_cmd->parsed() ? raster_cmd
                                               : render_cmd;
    if (command->get_option("--backend")->count() > 0 && backend != "simd") {
      err << "relief: error: --simd " << brief_text(simd_target) << " runs the simd backend, "
          << "not --backend " << backend << "; leave --backend out or give --backend simd\n";
      return kExitBadInput;
    }
    backend = "simd";
    try {
      force_simd_target(simd_target);
      simd_forced = true;
    } catch (const SimdTargetError& e) {
      err << "relief: error: --simd: " << brief_text(e.what(), 3 * kBriefChars) << "\n";
      return kExitBadInput;
    }
  }
  stages.backend = render.backend = *backend_from_name(backend);
  // The rasteriser has no double variant: its arithmetic is exact integers and doubles already.
  if (raster_cmd->parsed() &&
      (render.backend == Backend::kReferenceDouble || render.backend == Backend::kGl)) {
    err << "relief: error: --backend " << backend
        << " does not apply to relief raster (its arithmetic is already exact, and the GL "
           "rasteriser is what it is compared with); allowed: simd, reference\n";
    return kExitBadInput;
  }
  raster_options.simd = render.backend == Backend::kSimd;

  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }
  try {
    if (raster_cmd->parsed()) {
      const auto& v = raster_options.viewport;
      if (!v.empty() && (v[2] < 1 || v[3] < 1 || v[2] > 16384 || v[3] > 16384)) {
        err << "relief: error: --viewport " << v[2] << "x" << v[3]
            << " is out of range; allowed 1 <= width, height <= 16384\n";
        return kExitBadInput;
      }
      return run_raster_command(raster_options, out);
    }
    // The scene is validated completely before any work starts.
    const Scene scene = resolve_scene(scene_args.scene, scene_args.overrides);
    if (scene_cmd->parsed()) {
      out << scene_to_json(scene).dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
          << "\n";
      out.flush();
      if (!out) {  // a full disk or a closed pipe: the scene was not printed
        err << "relief: error: cannot write the scene to standard output\n";
        return kExitOutputError;
      }
      return kExitOk;
    }
    if (stages_cmd->parsed()) {
      return run_stages_command(scene, stages, out);
    }
    if (render_cmd->parsed()) {
      const std::string& o = render.output;
      if (!o.empty() && !has_extension(o, ".png")) {
        err << "relief: error: -o " << brief_text(o)
            << ": the image is written as PNG; give a file name ending in .png\n";
        return kExitBadInput;
      }
      for (const auto& [name, value, extension] :
           std::vector<std::tuple<const char*, const std::string*, const char*>>{
               {"--float", &render.float_output, ".pfm"},
               {"--depth", &render.depth_output, ".pfm"},
               {"--primitive", &render.primitive_output, ".bin"},
               {"--normal", &render.normal_output, ".pfm"},
               {"--height", &render.height_output, ".pfm"},
               {"--octaves", &render.octaves_output, ".pfm"}}) {
        if (!value->empty() && !has_extension(*value, extension)) {
          err << "relief: error: " << name << " " << brief_text(*value) << ": give a file name "
              << "ending in " << extension << "\n";
          return kExitBadInput;
        }
      }
      return run_render_command(scene, render, out);
    }
  } catch (const SceneError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const SoupError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const MemoryLimitError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const GlBackendError& e) {
    err << "relief: error: " << brief_text(e.what(), 4 * kBriefChars) << "\n";
    return kExitBadInput;
  } catch (const OutputError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitOutputError;
  } catch (const std::bad_alloc&) {
    // The estimate (job_memory.h) missed, or another process took the memory meanwhile.
    err << "relief: error: out of memory; nothing was written. Lower the image or grid size, or "
           "free memory and try again.\n";
    return kExitOutputError;
  } catch (const std::exception& e) {
    err << "relief: internal error: " << brief_text(e.what(), 3 * kBriefChars)
        << "; nothing was written. Please report this with the command line.\n";
    return kExitOutputError;
  }
  return kExitOk;
}

}  // namespace relief
