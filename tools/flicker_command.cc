#include "tools/flicker_command.h"

#include <charconv>
#include <cmath>
#include <iomanip>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "eval/flicker.h"
#include "eval/image_error.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/convergence_report.h"
#include "tools/distinct_paths.h"
#include "tools/render_report.h"
#include "tools/terminal_progress.h"

namespace relief {

namespace {

// A forward step of at most 10 km a frame; a turn of at most 45 degrees (beyond, the frames
// share too little to speak of flicker).
constexpr double kMaxForwardStep = 1e4;
constexpr double kMaxTurnStep = 45.0;

// Per band, then "all"; null where `counts` says the band had no pixels (no figure, not a
// perfect one).
nlohmann::ordered_json bands_json(const std::vector<double>& values,
                                  const std::vector<std::size_t>& counts) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (std::size_t b = 0; b <= kDistanceBands; ++b) {
    out[b < kDistanceBands ? kDistanceBandNames[b] : "all"] =
        counts[b] > 0 ? nlohmann::ordered_json(values[b]) : nullptr;
  }
  return out;
}

}  // namespace

CLI::App* add_flicker_command(CLI::App& app, FlickerOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "flicker",
      "Render a short camera move in real time and as ground truth and report, per band of "
      "distance, the real-time frames' mean FLIP against their truths and how much each "
      "sequence changes from frame to frame (real time changing more than the truth flickers)");
  cmd->add_option("--move", o.move, "forward (along the camera's horizontal direction) or turn")
      ->capture_default_str();
  cmd->add_option("--step", o.step,
                  "A frame's move: world units forward (|step| <= 1e4) or degrees of yaw "
                  "(|step| <= 45)")
      ->check(kNonEmptyNumber)
      ->capture_default_str();
  cmd->add_option("--frames", o.frames,
                  "Frames, 2 to " + std::to_string(kMaxFlickerFrames) + " (each a ground truth)")
      ->transform(integer_in(2, kMaxFlickerFrames))
      ->capture_default_str();
  cmd->add_option("--supersample", o.settings.supersample, "The truths' N x N samples a pixel")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  cmd->add_option("--grid-scale", o.settings.grid_scale, "The truths' grid: the scene's times this")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  cmd->add_option("--octave-epsilon", o.settings.octave_epsilon,
                  "The truths' octave threshold (relief reference)")
      ->check(kNonEmptyNumber)
      ->capture_default_str();
  o.json_option = cmd->add_option("--json", o.json, "Also write the figures as JSON");
  return cmd;
}

int run_flicker_command(const Scene& scene, const FlickerOptions& o, std::ostream& out,
                        std::ostream& err) {
  const auto refuse = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return kExitBadInput;
  };
  if (o.move != "forward" && o.move != "turn") {
    return refuse("--move " + brief_text(o.move) + " is not a move; allowed forward, turn");
  }
  const CameraMove move = o.move == "forward" ? CameraMove::kForward : CameraMove::kTurn;
  const double limit = move == CameraMove::kForward ? kMaxForwardStep : kMaxTurnStep;
  if (!(std::abs(o.step) <= limit)) {  // NaN fails
    return refuse("--step " + format_number(o.step) + " is out of range; allowed -" +
                  format_number(limit) + " to " + format_number(limit) +
                  (move == CameraMove::kForward ? " world units" : " degrees") + " for --move " +
                  o.move);
  }
  if (o.frames < 2 || o.frames > kMaxFlickerFrames) {
    return refuse("--frames " + std::to_string(o.frames) + " is out of range; allowed 2 to " +
                  std::to_string(kMaxFlickerFrames));
  }
  if (given_empty(o.json_option, o.json)) {
    return refuse("--json is empty; give a file name");
  }
  if (!o.json.empty()) {
    if (const std::optional<std::string> problem = output_path_problem(o.json)) {
      return refuse("--json " + *problem);
    }
    std::vector<CommandPath> paths = scene_input_paths(o.scene_arg, scene);
    paths.push_back({"--json", o.json});
    if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
      return refuse(*conflict);
    }
  }
  // The camera of the last frame must be one a scene may hold (the move is checked whole
  // before any frame is rendered): its position and yaw within the scene's limits.
  try {
    validate_scene(moved_scene(scene, move, o.step, o.frames - 1));
  } catch (const SceneError& e) {
    return refuse("--step " + format_number(o.step) + " over --frames " + std::to_string(o.frames) +
                  " moves the camera out of the scene's range: " + e.what());
  }
  GroundTruthSettings settings = o.settings;
  settings.distances = true;
  try {
    validate_ground_truth(scene, settings);
  } catch (const GroundTruthError& e) {
    return refuse(e.what());
  }
  // One truth at a time, one real-time frame, and two frames of each kept for the change.
  MemoryEstimate estimate = ground_truth_memory(scene, settings);
  FrameRequest request;
  request.outputs.linear = true;
  const MemoryEstimate frame = estimate_render_memory(scene, request.backend, request.outputs);
  estimate.add("a real-time frame", frame.total());
  const std::uintmax_t pixels =
      std::uintmax_t(scene.viewport.width) * std::uintmax_t(scene.viewport.height);
  estimate.add(
      "the previous frames and the error's planes",
      pixels * (2 * 12 + 4) + image_error_bytes(scene.viewport.width, scene.viewport.height));
  check_memory(estimate, o.budget, "this flicker measurement",
               "Lower --supersample or --grid-scale, or the scene's viewport or grid");
  request.max_bin_bytes = memory_left(estimate, o.budget);

  const SceneResources resources = load_scene_resources(scene);  // the camera's alone moves
  print_scene_notes(resources.notes, err);
  TerminalProgress progress("relief flicker", "frames");
  std::vector<FlickerFrame> frames;
  std::vector<float> last_realtime, last_truth;
  for (int k = 0; k < o.frames; ++k) {
    const Scene moved = moved_scene(scene, move, o.step, k);
    const Frame realtime = render_frame(moved, resources, request);
    const GroundTruthImage truth =
        render_ground_truth(moved, resources, settings, memory_left(estimate, o.budget));
    FlickerFrame f{banded_error(realtime.image.linear, truth.linear, truth), {}, {}};
    if (k > 0) {
      f.realtime = banded_change(last_realtime, realtime.image.linear, truth);
      f.truth = banded_change(last_truth, truth.linear, truth);
    }
    frames.push_back(std::move(f));
    last_realtime = realtime.image.linear;
    last_truth = truth.linear;
    progress.update(k + 1, o.frames);
  }
  progress.finish();
  const FlickerReport report = summarise_flicker(std::move(frames));

  if (!o.json.empty()) {
    nlohmann::ordered_json frames_json = nlohmann::ordered_json::array();
    for (const FlickerFrame& f : report.frames) {
      nlohmann::ordered_json entry = {{"mean_flip", f.error.all.mean_flip}};
      if (!f.realtime.empty()) {
        std::vector<std::size_t> band_pixels;
        for (const BandError& b : f.error.bands) {
          band_pixels.push_back(b.pixels);
        }
        band_pixels.push_back(f.error.all.pixels);
        entry["realtime_change"] = bands_json(f.realtime, band_pixels);
        entry["truth_change"] = bands_json(f.truth, band_pixels);
      }
      frames_json.push_back(entry);
    }
    const nlohmann::ordered_json summary = {
        {"move", o.move},
        {"step", o.step},
        {"frames", o.frames},
        {"mean_flip", bands_json(report.mean_flip, report.flip_frames)},
        {"realtime_change", bands_json(report.realtime_change, report.change_frames)},
        {"truth_change", bands_json(report.truth_change, report.change_frames)},
        {"per_frame", frames_json}};
    const std::string text = summary.dump(2) + "\n";
    write_file_atomically(
        o.json, std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(text.data()),
                                               text.size()));
  }
  out << std::fixed << std::setprecision(4) << o.move << " move, " << o.step
      << (move == CameraMove::kForward ? " world units" : " degrees") << " a frame, " << o.frames
      << " frames of " << scene.viewport.width << "x" << scene.viewport.height << "; truths at "
      << settings.supersample << "x" << settings.supersample << " samples, grid scale "
      << settings.grid_scale << "\n"
      << "    band            mean FLIP   change a frame (sRGB codes): real time    truth\n";
  for (std::size_t b = 0; b <= kDistanceBands; ++b) {
    out << "    " << std::left << std::setw(14)
        << (b < kDistanceBands ? kDistanceBandNames[b] : "all") << std::right;
    if (report.flip_frames[b] == 0) {  // an empty band: no figure
      out << std::setw(11) << "-" << std::setw(38) << "-" << std::setw(9) << "-"
          << "\n";
      continue;
    }
    out << std::setw(11) << report.mean_flip[b] << std::setw(38) << report.realtime_change[b]
        << std::setw(9) << report.truth_change[b] << "\n";
  }
  if (!o.json.empty()) {
    out << "wrote " << o.json << "\n";
  }
  return kExitOk;
}

}  // namespace relief
