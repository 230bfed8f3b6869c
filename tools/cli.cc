#include "tools/cli.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <new>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/job_memory.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scene_resources.h"
#include "tools/atomic_file.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/export_command.h"
#include "tools/flicker_command.h"
#include "tools/generate_command.h"
#include "tools/image_library.h"
#include "tools/panorama_command.h"
#include "tools/path_command.h"
#include "tools/reference_command.h"
#include "tools/shard.h"
#include "tools/soup.h"
#include "tools/stitch_command.h"
#include "tools/sweep_command.h"

namespace relief {

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  install_height_field_image_reader();  // EXR and TIFF height fields (image_library.h)
  CLI::App app{
      "Relief renders procedural fractal landscapes (Schneider, Boldte & Westermann, VMV 2006) "
      "with a deterministic CPU pipeline.\n"
      "Scenes are JSON files or built-in presets; every field can be overridden with --set.\n"
      "The scene reference is docs/scene-reference.md, the stage-by-stage map to the paper "
      "docs/stages.md.",
      "relief"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 bad input (nothing written), 1 output not written; compare "
      "and crosscheck exit as idiff does (their --help).\n"
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
      ->transform(integer_in(1, 1000));
  add_threads(stages_cmd, threads);
  std::string max_memory;
  add_max_memory(stages_cmd, max_memory);
  std::string backend = "simd";
  std::string simd_target;
  add_backend(stages_cmd, backend, simd_target);
  add_float_format(stages_cmd, stages.raw_format);
  // SCENE, --set, --threads and --max-memory: what the commands that render a scene take.
  const auto scene_job = [&](CLI::App* command) {
    add_scene_args(command, scene_args);
    add_threads(command, threads);
    add_max_memory(command, max_memory);
    return command;
  };

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
                             "Also write the linear radiance as a PFM or EXR file, by its "
                             "extension (default: the scene's output.float_image, if set)");
  // Extra per-pixel outputs of the fused back end, each written only when named.
  const std::vector<std::tuple<const char*, std::string*, const char*>> extra_outputs = {
      {"--depth", &render.depth_output, "window depth (reverse-Z) as a PFM or EXR file"},
      {"--primitive", &render.primitive_output,
       "winning triangle id per pixel, uint32 little-endian (4294967295: none)"},
      {"--normal", &render.normal_output, "unit normal as a 3-channel PFM or EXR file"},
      {"--height", &render.height_output, "world height of the terrain as a PFM or EXR file"},
      {"--octaves", &render.octaves_output, "octave count nu as a PFM or EXR file"}};
  std::vector<const CLI::Option*> extra_options;
  for (const auto& [name, target, what] : extra_outputs) {
    extra_options.push_back(render_cmd->add_option(
        name, *target, std::string("Also write the ") + what + " (PFM rows bottom to top)"));
  }
  render_cmd
      ->add_option("--repeat", render.repeat,
                   "Render this many times and report the median stage times")
      ->transform(integer_in(1, 1000));
  add_threads(render_cmd, threads);
  add_max_memory(render_cmd, max_memory);
  add_backend(render_cmd, backend, simd_target);
  add_shard_option(render_cmd, render.shard, "image's rows of tiles");
  render_cmd->add_flag("--stats", render.stats,
                       "Print per stage whether it ran or was skipped, its median time and its "
                       "work counters (vertices evaluated, triangles set up, texture fetches...)");
  const CLI::Option* render_stats_json = render_cmd->add_option(
      "--stats-json", render.stats_json, "Also write the --stats report as a JSON file, for CI");

  RasterOptions raster_options;
  CLI::App* raster_cmd = add_raster_command(app, raster_options);
  const CLI::Option* raster_out = raster_cmd->get_option("--out");
  add_backend(raster_cmd, backend, simd_target);
  add_threads(raster_cmd, threads);
  add_max_memory(raster_cmd, max_memory);

  CLI::App* info_cmd = app.add_subcommand(
      "info",
      "Print the version, how this build was compiled and its SIMD targets: those "
      "compiled in, those this CPU runs, and the one the simd backend uses.");

  CompareOptions compare;
  CLI::App* compare_cmd = add_compare_command(app, compare);

  CrosscheckOptions crosscheck;
  CLI::App* crosscheck_cmd = scene_job(add_crosscheck_command(app, crosscheck));

  // The ground truth and the error of a render against it (reference_command.h).
  ReferenceOptions reference;
  CLI::App* reference_cmd = scene_job(add_reference_command(app, reference));
  FlickerOptions flicker;  // a camera move in real time and as truth (flicker_command.h)
  CLI::App* flicker_cmd = scene_job(add_flicker_command(app, flicker));
  ErrorOptions error_options;
  CLI::App* error_cmd = add_error_command(app, error_options);
  add_max_memory(error_cmd, max_memory);
  // Frame time against error over the speed knobs (sweep_command.h).
  SweepOptions sweep;
  CLI::App* sweep_cmd = scene_job(add_sweep_command(app, sweep));

  // The stability stress suite (stress_command.cc).
  StressOptions stress;
  CLI::App* stress_cmd = add_stress_command(app, stress);
  add_scene_args(stress_cmd, scene_args);
  add_threads(stress_cmd, threads);
  // A camera path down to a planet (path_command.h).
  PathOptions path;
  CLI::App* path_cmd = scene_job(add_path_command(app, path));
  add_backend(path_cmd, backend, simd_target);
  PanoramaOptions panorama;  // the scene all around its camera (panorama_command.h)
  CLI::App* panorama_cmd = scene_job(add_panorama_command(app, panorama));
  add_backend(panorama_cmd, backend, simd_target);
  ExportOptions export_options;  // the terrain as files other tools read (export_command.h)
  CLI::App* export_cmd = scene_job(add_export_command(app, export_options));
  StitchOptions stitch;  // the parts of --shard put together (stitch_command.h)
  add_max_memory(add_stitch_command(app, stitch), max_memory);
  GenerateOptions generate;  // height maps by the seeds' generators (generate_command.h)
  add_max_memory(add_generate_command(app, generate), max_memory);

  // CLI11 answers an unknown command with "A subcommand is required"; say what is wrong.
  std::string commands;
  bool known = false;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    commands += (commands.empty() ? "" : ", ") + command->get_name();
    known = known || (args.size() > 1 && args[1] == command->get_name());
  }
  if (args.size() > 1 && !args[1].empty() && args[1][0] != '-' && !known) {
    err << "relief: error: unknown command '" << brief_text(args[1]) << "'; commands: " << commands
        << "\nRun 'relief --help' for usage.\n";
    return kExitBadInput;
  }
  // compare and crosscheck exit as idiff does, where 2 means the images differ: their bad
  // input is 4, crosscheck's unwritten output 5.
  const bool idiff_codes = args.size() > 1 && (args[1] == "compare" || args[1] == "crosscheck");
  const int bad_input = idiff_codes ? exit_code(CompareVerdict::kFileError) : kExitBadInput;
  const int output_error =
      args.size() > 1 && args[1] == "crosscheck" ? kCrosscheckOutputError : kExitOutputError;
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
    return bad_input;
  }
  if (compare_cmd->parsed()) {
    return run_compare_command(compare, out, err);
  }
  std::vector<std::pair<const CLI::Option*, std::string>> named = {
      {stages_out, stages.out_dir},        {render_out, render.output},
      {render_float, render.float_output}, {render_stats_json, render.stats_json},
      {raster_out, raster_options.prefix}, {crosscheck.out_option, crosscheck.out_dir}};
  for (std::size_t k = 0; k < extra_options.size(); ++k) {
    named.emplace_back(extra_options[k], *std::get<1>(extra_outputs[k]));
  }
  for (const auto& [option, value] : named) {
    if (given_empty(option, value)) {
      err << "relief: error: " << option->get_name()
          << " is empty; give a file or directory name\n";
      return bad_input;
    }
  }
  if (raster_cmd->parsed() && raster_options.soup.empty()) {
    err << "relief: error: FILE is empty; give the triangle soup's file name\n";
    return bad_input;
  }
  for (CLI::App* command : {scene_cmd, stages_cmd, render_cmd, crosscheck_cmd, reference_cmd,
                            sweep_cmd, stress_cmd, path_cmd, panorama_cmd, export_cmd}) {
    if (command->parsed() && given_empty(command->get_option("SCENE"), scene_args.scene)) {
      err << "relief: error: SCENE is empty; give a scene file or a preset name, or leave it "
             "out for the default scene\n";
      return bad_input;
    }
  }
  if (raster_cmd->parsed()) {
    // PREFIX names files: "out/" or "." would write hidden files named ".json", "..json".
    const std::string file = std::filesystem::path(raster_options.prefix).filename().string();
    if (file.empty() || file == "." || file == "..") {
      err << "relief: error: --out " << brief_text(raster_options.prefix)
          << " has no file name part; give a prefix such as out/soup\n";
      return bad_input;
    }
  }
  const MemoryBudget budget = memory_budget(parse_memory_size(max_memory), max_memory);
  stages.budget = render.budget = raster_options.budget = crosscheck.budget = budget;
  reference.budget = flicker.budget = error_options.budget = sweep.budget = path.budget =
      stitch.budget = generate.budget = panorama.budget = export_options.budget = budget;
  reference.scene_arg = crosscheck.scene_arg = flicker.scene_arg = panorama.scene_arg =
      export_options.scene_arg = scene_args.scene;
  if (error_cmd->parsed()) {
    return run_error_command(error_options, out, err);
  }
  crosscheck.cpu_backend = *backend_from_name(crosscheck.cpu_backend_name);
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
      return bad_input;
    }
    backend = "simd";
    try {
      force_simd_target(simd_target);
      simd_forced = true;
    } catch (const SimdTargetError& e) {
      err << "relief: error: --simd: " << brief_text(e.what(), 3 * kBriefChars) << "\n";
      return bad_input;
    }
  }
  stages.backend = render.backend = path.backend = panorama.backend = *backend_from_name(backend);
  // The rasteriser has no double variant: its arithmetic is exact integers and doubles already.
  if (raster_cmd->parsed() &&
      (render.backend == Backend::kReferenceDouble || render.backend == Backend::kGl)) {
    err << "relief: error: --backend " << backend
        << " does not apply to relief raster (its arithmetic is already exact, and the GL "
           "rasteriser is what it is compared with); allowed: simd, reference\n";
    return bad_input;
  }
  raster_options.simd = render.backend == Backend::kSimd;

  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }
  try {
    if (app.got_subcommand("stitch")) {
      return run_stitch_command(stitch, out, err);
    }
    if (app.got_subcommand("generate")) {
      return run_generate_command(generate, out, err);
    }
    if (raster_cmd->parsed()) {
      const auto& v = raster_options.viewport;
      if (!v.empty() && (v[2] < 1 || v[3] < 1 || v[2] > 16384 || v[3] > 16384)) {
        err << "relief: error: --viewport " << v[2] << "x" << v[3]
            << " is out of range; allowed 1 <= width, height <= 16384\n";
        return bad_input;
      }
      return run_raster_command(raster_options, out);
    }
    // The scene is validated completely before any work starts.
    const Scene scene = resolve_scene(scene_args.scene, scene_args.overrides);
    const ProtectedInputs inputs(scene_input_paths(scene_args.scene, scene));
    if (scene_cmd->parsed()) {
      // The files and the rules that need them (a planet's depth) are checked as render checks
      // them: a scene that prints is one that renders.
      check_memory(estimate_scene_resources_memory(scene), budget, "loading the scene's files",
                   "Use smaller textures, sketch or basis images");
      print_scene_notes(load_scene_resources(scene).notes, err);
      out << scene_json_text(scene);
      out.flush();
      if (!out) {  // a full disk or a closed pipe: the scene was not printed
        err << "relief: error: cannot write the scene to standard output\n";
        return output_error;
      }
      return kExitOk;
    }
    // The commands that take the validated scene; the first parsed one runs.
    const std::vector<std::pair<CLI::App*, std::function<int()>>> scene_commands = {
        {stages_cmd, [&] { return run_stages_command(scene, stages, out, err); }},
        {crosscheck_cmd, [&] { return run_crosscheck_command(scene, crosscheck, out, err); }},
        {reference_cmd, [&] { return run_reference_command(scene, reference, out, err); }},
        {flicker_cmd, [&] { return run_flicker_command(scene, flicker, out, err); }},
        {sweep_cmd, [&] { return run_sweep_command(scene, sweep, out, err); }},
        {stress_cmd, [&] { return run_stress_command(scene, stress, out, err); }},
        {path_cmd, [&] { return run_path_command(scene, path, out, err); }},
        {panorama_cmd, [&] { return run_panorama_command(scene, panorama, out, err); }},
        {export_cmd, [&] { return run_export_command(scene, export_options, out, err); }},
        {render_cmd, [&] {
           const int refused = check_render_paths(scene, scene_args.scene, render, err);
           return refused != 0 ? refused : run_render_command(scene, render, out, err);
         }}};
    for (const auto& [command, run] : scene_commands) {
      if (command->parsed()) {
        return run();
      }
    }
  } catch (const std::runtime_error& e) {
    // What the user can act on (the scene, the soup, the memory, GL or OpenImageIO missing, an
    // output naming an input) is bad input; the rest falls through to the handlers below.
    if (dynamic_cast<const SceneError*>(&e) || dynamic_cast<const SoupError*>(&e) ||
        dynamic_cast<const MemoryLimitError*>(&e) || dynamic_cast<const GlBackendError*>(&e) ||
        dynamic_cast<const ImageLibraryError*>(&e) || dynamic_cast<const OutputAliasError*>(&e) ||
        dynamic_cast<const ShardError*>(&e)) {
      const bool gl = dynamic_cast<const GlBackendError*>(&e) != nullptr;  // a driver's log
      err << "relief: error: " << (gl ? brief_text(e.what(), 4 * kBriefChars) : e.what()) << "\n";
      return bad_input;
    }
    if (dynamic_cast<const OutputError*>(&e)) {
      err << "relief: error: " << e.what() << "\n";
      return output_error;
    }
    err << "relief: internal error: " << brief_text(e.what(), 3 * kBriefChars)
        << "; nothing was written. Please report this with the command line.\n";
    return output_error;
  } catch (const std::bad_alloc&) {
    // The estimate (job_memory.h) missed, or another process took the memory meanwhile.
    err << "relief: error: out of memory; nothing was written. Lower the image or grid size (or "
           "lighting.shadow_resolution), or free memory and try again.\n";
    return output_error;
  } catch (const std::exception& e) {
    err << "relief: internal error: " << brief_text(e.what(), 3 * kBriefChars)
        << "; nothing was written. Please report this with the command line.\n";
    return output_error;
  }
  return kExitOk;
}

}  // namespace relief
