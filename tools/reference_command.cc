// `relief reference [SCENE] -o FILE.png [--float FILE.exr|.pfm]`: the ground-truth render
// (eval/ground_truth.h; docs/ground-truth.md). This file parses its options and writes its
// files; the render is the pipeline's.
#include <chrono>
#include <climits>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/scene/json_input.h"
#include "eval/convergence.h"
#include "eval/ground_truth.h"
#include "eval/height_error.h"
#include "eval/image_error.h"
#include "image/crc32.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/convergence_report.h"
#include "tools/distinct_paths.h"
#include "tools/float_image_file.h"
#include "tools/reference_command.h"
#include "tools/render_report.h"
#include "tools/shard.h"
#include "tools/terminal_progress.h"

namespace relief {

namespace {

// FILE.png -> FILE.exr: the float image beside the PNG unless --float names one.
std::string float_name(const std::string& png) {
  return png.substr(0, png.size() - 4) + ".exr";
}

std::string settings_text(const GroundTruthSettings& s) {
  std::ostringstream text;
  text << "supersample=" << s.supersample << " grid_scale=" << s.grid_scale
       << " octave_epsilon=" << std::setprecision(17) << s.octave_epsilon;
  return text.str();
}

void print_height_error(std::ostream& out, const Scene& scene) {
  const std::optional<NoiseLattice> basis = load_basis_grid(scene);
  const NoiseLattice lattice =
      basis ? *basis : make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const std::optional<HeightSketch> sketch = load_height_sketch(scene);
  const VertexHeightError e =
      vertex_height_error(scene, lattice, Backend::kSimd, sketch ? &*sketch : nullptr);
  out << std::scientific << std::setprecision(3) << "  float heights against double at the same "
      << "domain points (scene's grid " << scene.grid.width << "x" << scene.grid.height << ", "
      << e.vertices << " vertices): max " << e.max << ", rms " << e.rms << " world units ("
      << e.max / e.amplitude << " and " << e.rms / e.amplitude << " of the amplitude)\n"
      << std::fixed;
}

}  // namespace

CLI::App* add_reference_command(CLI::App& app, ReferenceOptions& options) {
  CLI::App* command = app.add_subcommand(
      "reference",
      "Render the scene's ground truth: the stages in double, octaves summed until their "
      "amplitude is below --octave-epsilon of a pixel's footprint, a finer grid "
      "(--grid-scale) and N x N samples per pixel (--supersample), box-filtered in linear "
      "radiance. Writes an sRGB PNG and the linear radiance (EXR or PFM). Slow by design.");
  options.output_option = command->add_option("-o,--output", options.output,
                                              "PNG file to write (default reference.png)");
  options.float_option = command->add_option(
      "--float", options.float_output,
      "The linear radiance as a PFM or EXR file, by its extension (default: -o's name with .exr)");
  command
      ->add_option("--supersample", options.settings.supersample,
                   "N: N x N samples per pixel, averaged with a box filter in linear radiance "
                   "(1-16, and the supersampled viewport at most 16384 a side)")
      ->transform(integer_in(INT_MIN, INT_MAX))  // the range: validate_ground_truth
      ->capture_default_str();
  command
      ->add_option("--grid-scale", options.settings.grid_scale,
                   "Projected-grid vertices per axis: the scene's times this (1-16, and at most "
                   "8192 a side)")
      ->transform(integer_in(INT_MIN, INT_MAX))  // the range: validate_ground_truth
      ->capture_default_str();
  command
      ->add_option("--octave-epsilon", options.settings.octave_epsilon,
                   "Sum octaves while their amplitude is at least this fraction of a pixel's "
                   "footprint at the vertex's distance (1e-6 to 1); the scene's last_octave caps "
                   "them")
      ->check(kNonEmptyNumber)
      ->capture_default_str();
  add_shard_option(command, options.shard,
                   "image's rows, in steps of lcm(64, N) / N rows for N x N samples");
  command->add_flag("--converge", options.converge,
                    "Also render the frame at twice the settings (samples a pixel and grid "
                    "each way, half the octave epsilon) and report the difference: mean FLIP "
                    "and PSNR over the image and per band of distance (sky, near, middle and far "
                    "thirds of the terrain). Costs about 16 times the render");
  options.json_option =
      command->add_option("--json", options.json, "With --converge: the figures as a JSON file");
  command->add_flag("--stats", options.stats,
                    "Also print the stage times of the supersampled frame and the float error "
                    "of the heights at the scene's own grid vertices");
  return command;
}

int run_reference_command(const Scene& scene, const ReferenceOptions& options, std::ostream& out,
                          std::ostream& err) {
  for (const auto& [option, value] : {std::pair{options.output_option, &options.output},
                                      std::pair{options.float_option, &options.float_output},
                                      std::pair{options.json_option, &options.json}}) {
    if (given_empty(option, *value)) {
      err << "relief: error: " << option->get_name() << " is empty; give a file name\n";
      return kExitBadInput;
    }
  }
  if (!has_extension(options.output, ".png")) {
    err << "relief: error: -o " << brief_text(options.output)
        << ": the image is written as PNG; give a file name ending in .png\n";
    return kExitBadInput;
  }
  const std::string float_path =
      options.float_output.empty() ? float_name(options.output) : options.float_output;
  if (!float_format_of(float_path)) {
    err << "relief: error: --float " << brief_text(float_path)
        << ": give a file name ending in .pfm or .exr\n";
    return kExitBadInput;
  }
  if (!options.json.empty() && !options.converge) {
    err << "relief: error: --json " << brief_text(options.json)
        << " writes the figures of --converge; give --converge too\n";
    return kExitBadInput;
  }
  if (options.converge && !options.shard.empty()) {
    err << "relief: error: --converge measures the whole image; leave out --shard "
        << brief_text(options.shard) << "\n";
    return kExitBadInput;
  }
  std::vector<CommandPath> paths = scene_input_paths(options.scene_arg, scene);
  paths.push_back({"-o", options.output});
  paths.push_back({"--float", float_path});
  if (!options.json.empty()) {
    paths.push_back({"--json", options.json});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    err << "relief: error: " << *conflict << "\n";
    return kExitBadInput;
  }
  for (const CommandPath& path : paths) {  // the outputs, before the slow render
    if (path.output) {
      if (const std::optional<std::string> problem = output_path_problem(path.path)) {
        err << "relief: error: " << path.option << " " << *problem << "\n";
        return kExitBadInput;
      }
    }
  }
  GroundTruthSettings settings = options.settings;
  settings.distances = options.converge;
  const GroundTruthSettings doubled = doubled_settings(settings);
  try {
    if (options.converge) {
      validate_convergence(scene, settings);
    } else {
      validate_ground_truth(scene, settings);
    }
  } catch (const GroundTruthError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  }
  // --shard: a band of whole steps of the image's rows (shard.h), its PNG and float file.
  std::optional<Shard> shard;
  FrameRows rows;
  if (!options.shard.empty()) {
    shard = parse_shard(options.shard, std::getenv);
    const ShardSpan band = shard_rows(scene.viewport.height, *shard,
                                      ground_truth_shard_unit(options.settings.supersample));
    rows = {band.begin, band.end};
  }
  const MemoryEstimate estimate = ground_truth_memory(scene, settings, rows);
  check_memory(estimate, options.budget, "this reference render",
               "Lower --supersample or --grid-scale, or the scene's viewport or grid");
  // --converge: the doubled render while the first image is kept, then FLIP's planes.
  MemoryEstimate doubled_estimate = ground_truth_memory(scene, doubled);
  if (options.converge) {
    const std::uintmax_t pixels =
        std::uintmax_t(scene.viewport.width) * std::uintmax_t(scene.viewport.height);
    doubled_estimate.add("the first image and its distances", pixels * (12 + 3 + 4));
    doubled_estimate.add("the error's planes",
                         image_error_bytes(scene.viewport.width, scene.viewport.height));
    check_memory(doubled_estimate, options.budget, "this reference render at twice its settings",
                 "Lower --supersample or --grid-scale, or the scene's viewport or grid");
  }

  const auto start = std::chrono::steady_clock::now();
  const SceneResources resources = load_scene_resources(scene);  // validates texture files
  print_scene_notes(resources.notes, err);
  TerminalProgress progress("relief reference", "bands");
  const GroundTruthImage image = render_ground_truth(
      scene, resources, settings, memory_left(estimate, options.budget),
      [&](int done, int total) { progress.update(done, total); }, rows);
  progress.finish();
  std::optional<ConvergenceReport> convergence;
  if (options.converge) {
    TerminalProgress twice("relief reference at twice the settings", "bands");
    const GroundTruthImage finer = render_ground_truth(
        scene, resources, doubled, memory_left(doubled_estimate, options.budget),
        [&](int done, int total) { twice.update(done, total); });
    twice.finish();
    convergence = compare_truths(image, finer, settings);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<ImageText> metadata = scene_metadata(scene);
  metadata.push_back({"relief:reference", settings_text(options.settings)});
  const std::vector<unsigned char> float_file =
      encode_float_image(*float_format_of(float_path), image.width, image.height, 3, image.linear,
                         3 * std::size_t(image.width), metadata);
  std::vector<ImageText> png_text = metadata;
  if (shard) {  // the PNG names its float file, its size and CRC (shard.h)
    const int height = scene.viewport.height;
    png_text.push_back(
        {std::string(kShardKey),
         shard_record_text({*shard,
                            std::string(backend_name(Backend::kReferenceDouble)),
                            image.width,
                            height,
                            height - (image.first_row + image.height),
                            image.height,
                            ground_truth_shard_unit(options.settings.supersample),
                            {{"float", companion_file_name(options.output, float_path),
                              float_file.size(), crc32(float_file)}}})});
  }
  OutputSet files;  // both appear, or neither
  files.add(options.output, encode_png_rgb(image.width, image.height, image.srgb, png_text));
  files.add(float_path, float_file);
  std::string json_text;
  if (convergence && !options.json.empty()) {
    json_text = convergence_json(*convergence).dump(2) + "\n";
    files.add(options.json,
              std::span<const unsigned char>(
                  reinterpret_cast<const unsigned char*>(json_text.data()), json_text.size()));
  }
  files.commit();

  const GroundTruthSettings& s = options.settings;
  const Scene big = supersampled_scene(scene, s);
  out << std::fixed << std::setprecision(3) << image.width << "x" << image.height
      << " reference: " << s.supersample << "x" << s.supersample << " samples a pixel ("
      << big.viewport.width << "x" << big.viewport.height << " in " << image.bands
      << " band(s)), grid " << big.grid.width << "x" << big.grid.height
      << ", backend reference-double\n"
      << "  octaves summed down to " << s.octave_epsilon << " of a pixel's footprint; ";
  if (std::isinf(image.lod.cap_distance)) {  // a height field without the fractal
    out << "the height field's own samples (level 0) everywhere\n";
  } else {
    out << "all " << int(image.lod.lod.nu_max) << " of the scene's octaves (the cap) within "
        << std::setprecision(1) << image.lod.cap_distance << " world units of the camera\n";
  }
  out << std::setprecision(3) << "  " << seconds << " s, estimated peak memory "
      << estimate.describe() << "\n";
  if (options.stats) {
    RenderRuns runs;
    runs.add(image.stats);
    print_stage_stats(out, runs);
    print_height_error(out, scene);
  }
  if (convergence) {
    print_convergence(out, *convergence);
    out << "  the render at twice the settings: estimated peak memory "
        << doubled_estimate.describe() << "\n";
  }
  if (shard) {
    out << "  shard " << shard->index << "/" << shard->count << ": image rows "
        << scene.viewport.height - (image.first_row + image.height) << " to "
        << scene.viewport.height - image.first_row - 1 << " (top to bottom) of "
        << scene.viewport.height << "\n";
  }
  out << "wrote " << options.output << " and " << float_path << "\n";
  return kExitOk;
}

}  // namespace relief
