// `relief sweep [SCENE] --out DIR`: the ground truth rendered once (or read back), then every
// configuration of the plan (eval/sweep_plan.h) rendered, timed and measured against it;
// the CSV, the gnuplot script and its plot written into DIR together (docs/sweep.md).
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "eval/sweep.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/distinct_paths.h"
#include "tools/float_image_file.h"
#include "tools/gnuplot.h"
#include "tools/image_file.h"
#include "tools/sweep_command.h"
#include "tools/sweep_report.h"
#include "tools/terminal_progress.h"

namespace relief {

namespace {

namespace fs = std::filesystem;

struct Reference {
  std::vector<float> linear;  // RGB, rows bottom to top
  std::string origin;         // how it was made, for the metadata and the plot
};

// A reference image given with --reference: linear radiance (EXR or PFM) of the scene's
// viewport. Throws ImageFileError naming what is wrong.
Reference read_reference(const std::string& path, const Scene& scene) {
  ImageFile file(path);
  if (file.format() != "openexr" && !has_extension(path, ".pfm")) {
    throw ImageFileError("--reference " + brief_text(path) + " is a " + file.format() +
                         " image; give the linear radiance of relief reference (EXR or PFM)");
  }
  if (file.width() != scene.viewport.width || file.height() != scene.viewport.height) {
    throw ImageFileError("--reference " + brief_text(path) + " is " + std::to_string(file.width()) +
                         "x" + std::to_string(file.height()) + "; the scene's viewport is " +
                         std::to_string(scene.viewport.width) + "x" +
                         std::to_string(scene.viewport.height));
  }
  if (file.channels() < 3) {
    throw ImageFileError("--reference " + brief_text(path) + " has " +
                         std::to_string(file.channels()) + " channel(s); give an RGB image");
  }
  // The scene the reference was made of (its metadata; PFM holds none) must be this one, output
  // paths apart: a reference of another scene measures nothing.
  if (const std::optional<std::string> text = file.text(std::string(kSceneKey))) {
    nlohmann::json made = nlohmann::json::parse(*text, nullptr, false);
    nlohmann::json here = nlohmann::json::parse(scene_json_text(scene));
    if (made.is_object()) {
      made.erase("output");
    }
    here.erase("output");
    if (made != here) {
      throw ImageFileError("--reference " + brief_text(path) + " was rendered from another " +
                           "scene (its " + std::string(kSceneKey) + " metadata differs from " +
                           "this scene); render the reference of this scene, or leave " +
                           "--reference out");
    }
  }
  const FloatImage image = file.read();  // top row first
  if (const NonFiniteCount bad = count_non_finite(image); bad.total() > 0) {
    throw ImageFileError("--reference " + brief_text(path) + " holds " + bad.describe() +
                         "; a reference is finite radiance");
  }
  Reference out;
  out.origin = "read from " + fs::path(path).filename().string();
  out.linear.resize(3 * std::size_t(image.width) * image.height);
  for (int y = 0; y < image.height; ++y) {
    const std::size_t source = std::size_t(image.height - 1 - y) * image.width;
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        out.linear[3 * (std::size_t(y) * image.width + x) + c] =
            image.pixels[(source + x) * image.channels + c];
      }
    }
  }
  return out;
}

Reference render_reference(const Scene& scene, const GroundTruthSettings& settings,
                           std::uint64_t max_bin_bytes, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const SceneResources resources = load_scene_resources(scene);
  TerminalProgress progress("relief sweep: reference", "bands");
  GroundTruthImage image =
      render_ground_truth(scene, resources, settings, max_bin_bytes,
                          [&](int done, int total) { progress.update(done, total); });
  progress.finish();
  std::ostringstream origin;
  origin << "supersample=" << settings.supersample << " grid_scale=" << settings.grid_scale
         << " octave_epsilon=" << settings.octave_epsilon;
  out << std::fixed << std::setprecision(1) << "reference (" << origin.str()
      << "): " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
      << " s\n";
  return {std::move(image.linear), origin.str()};
}

std::string plot_subtitle(const Scene& scene, const Reference& reference, int repeat, int threads) {
  std::ostringstream text;
  text << scene.viewport.width << "x" << scene.viewport.height << ", grid " << scene.grid.width
       << "x" << scene.grid.height << "; reference " << reference.origin << "; median of " << repeat
       << " frame(s) on " << threads << " thread(s)";
  return text.str();
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Render the scene with every knob that trades speed for accuracy varied one at a time "
      "(grid, LOD criterion and bias, octaves, fractional octave, interpolant, supersampling, "
      "backend) and a few combinations; time each (median of --repeat frames) and measure its "
      "error against the ground truth (relief reference). Writes DIR/sweep.csv, the plot "
      "DIR/sweep.png (gnuplot) with its script DIR/sweep.gp, and the reference.");
  options.out_option =
      command->add_option("--out", options.out_dir, "Output directory (created if missing)")
          ->required();
  options.reference_option = command->add_option(
      "--reference", options.reference,
      "Reuse this reference (the EXR or PFM of relief reference for the same scene) instead of "
      "rendering it");
  command
      ->add_option("--repeat", options.repeat,
                   "Frames per configuration; the median time is reported (1-1000)")
      ->transform(integer_in(1, 1000))
      ->capture_default_str();
  command->add_flag("--quick", options.quick,
                    "A small subset of the configurations (for tests and a first look)");
  command
      ->add_option("--reference-supersample", options.settings.supersample,
                   "The rendered reference's N x N samples per pixel (relief reference "
                   "--supersample)")
      ->capture_default_str();
  command
      ->add_option("--reference-grid-scale", options.settings.grid_scale,
                   "The rendered reference's grid, the scene's times this (relief reference "
                   "--grid-scale)")
      ->capture_default_str();
  return command;
}

int run_sweep_command(const Scene& scene, const SweepOptions& options, std::ostream& out,
                      std::ostream& err) {
  for (const auto& [option, value] : {std::pair{options.out_option, &options.out_dir},
                                      std::pair{options.reference_option, &options.reference}}) {
    if (given_empty(option, *value)) {
      err << "relief: error: " << option->get_name() << " is empty; give a name\n";
      return kExitBadInput;
    }
  }
  std::vector<CommandPath> paths = {{"--reference", options.reference, false}};
  for (const char* name :
       {"reference.png", "reference.exr", "sweep.csv", "sweep.gp", "sweep.png"}) {
    paths.push_back({"--out's " + std::string(name), fs::path(options.out_dir) / name});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    err << "relief: error: " << *conflict << "\n";
    return kExitBadInput;
  }
  std::error_code ec;
  if (fs::exists(options.out_dir, ec) && !fs::is_directory(options.out_dir, ec)) {
    // An output that cannot be written, as stages, path and crosscheck say it (exit 1).
    err << "relief: error: cannot write into " << brief_text(options.out_dir)
        << ": it exists and is not a directory\n";
    return kExitOutputError;
  }
  const bool render_truth = options.reference.empty();
  if (render_truth) {
    try {
      validate_ground_truth(scene, options.settings);
    } catch (const GroundTruthError& e) {
      // The ground truth names its own options (--supersample, --grid-scale): here they are
      // --reference-supersample and --reference-grid-scale.
      std::string message = e.what();
      for (const auto& [own, here] :
           {std::pair<std::string, std::string>{"--supersample", "--reference-supersample"},
            {"--grid-scale", "--reference-grid-scale"}}) {
        for (std::size_t at = message.find(own); at != std::string::npos;
             at = message.find(own, at + here.size())) {
          message.replace(at, own.size(), here);
        }
      }
      err << "relief: error: " << message << "\n";
      return kExitBadInput;
    }
  }
  Reference reference;
  if (!render_truth) {
    try {
      reference = read_reference(options.reference, scene);
    } catch (const ImageFileError& e) {
      err << "relief: error: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  const SweepPlan plan = plan_sweep(
      scene, options.quick,
      options.quick ? std::optional<std::string>("not in --quick") : gl_unavailable_reason());
  MemoryEstimate estimate = sweep_memory(scene, plan.configurations);
  if (render_truth) {
    const MemoryEstimate truth = ground_truth_memory(scene, options.settings);
    if (truth.total() > estimate.total()) {
      estimate = truth;
    }
  }
  estimate.add("reference image",
               12 * std::uintmax_t(scene.viewport.width) * std::uintmax_t(scene.viewport.height));
  check_memory(estimate, options.budget, "this sweep",
               "Lower the scene's viewport or grid, or use --quick");

  const int threads = tbb::this_task_arena::max_concurrency();
  out << "relief sweep: " << plan.configurations.size() << " configurations, " << options.repeat
      << " frame(s) each, " << threads << " thread(s)\n";
  for (const SweepSkipped& s : plan.skipped) {
    out << "  skipped " << s.name << ": " << brief_text(s.reason, 4 * kBriefChars) << "\n";
  }
  if (render_truth) {
    reference =
        render_reference(scene, options.settings, memory_left(estimate, options.budget), out);
  }
  TerminalProgress progress("relief sweep", "frames");
  const std::vector<SweepRow> rows = run_sweep(
      scene, plan.configurations, reference.linear, options.repeat,
      memory_left(estimate, options.budget),
      [&](int done, int total, std::string_view name) { progress.update(done, total, name); });
  progress.finish();

  const std::string csv = sweep_csv(rows);
  const std::string script =
      sweep_gnuplot_script(rows, plot_subtitle(scene, reference, options.repeat, threads));
  const GnuplotResult plot = run_gnuplot(script);

  const std::size_t pixels = std::size_t(scene.viewport.width) * scene.viewport.height;
  std::vector<std::uint8_t> srgb(3 * pixels);
  for (std::size_t k = 0; k < srgb.size(); ++k) {
    srgb[k] = srgb_byte(reference.linear[k]);
  }
  std::vector<ImageText> metadata = scene_metadata(scene);
  metadata.push_back({"relief:reference", reference.origin});
  const fs::path dir = options.out_dir;
  OutputDirectory directory(dir);
  OutputSet files;  // all appear together, or none
  files.add(dir / "reference.png",
            encode_png_rgb(scene.viewport.width, scene.viewport.height, srgb, metadata));
  files.add(dir / "reference.exr",
            encode_float_image(FloatFormat::kExr, scene.viewport.width, scene.viewport.height, 3,
                               reference.linear, 3 * std::size_t(scene.viewport.width), metadata));
  const auto bytes = [](const std::string& text) {
    return std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(text.data()),
                                          text.size());
  };
  files.add(dir / "sweep.csv", bytes(csv));
  files.add(dir / "sweep.gp", bytes(script));
  if (plot.status == GnuplotResult::Status::kDrawn) {
    files.add(dir / "sweep.png", plot.png);
  }
  files.commit();
  directory.keep();

  print_sweep_table(out, rows);
  print_default_verdict(out, rows);
  out << "wrote " << (dir / "sweep.csv").string() << ", sweep.gp, reference.png, reference.exr";
  if (plot.status == GnuplotResult::Status::kDrawn) {
    out << ", sweep.png\n";
    return kExitOk;
  }
  out << "\n";
  if (plot.status == GnuplotResult::Status::kMissing) {
    err << "relief: warning: no plot: " << plot.message
        << " (install Debian's gnuplot-nox); the CSV and the script are written, run "
           "'gnuplot -c sweep.gp sweep.png' in "
        << brief_text(dir.string()) << " later\n";
    return kExitOk;
  }
  err << "relief: error: no plot: " << brief_text(plot.message, 4 * kBriefChars)
      << "; the CSV and the script are written\n";
  return kExitOutputError;
}

}  // namespace relief
