#include "tools/path_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/job_memory.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/shard.h"
#include "tools/terminal_progress.h"

namespace relief {

namespace {

constexpr int kMaxFrames = kMaxPathFrames;
constexpr double kMinPitchDeg = -89.0, kMaxPitchDeg = 89.0;

}  // namespace

CLI::App* add_path_command(CLI::App& app, PathOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "path",
      "Renders a radial descent of the camera (docs/planet.md) as DIR/frame_0000.png, ...: the "
      "altitude above terrain.base_height log-uniform from --from-altitude to --to-altitude, "
      "the pitch easing from the scene's to --to-pitch");
  cmd->add_option("--out", options.out_dir, "Directory for the frames")->required();
  cmd->add_option("--frames", options.frames, "Number of frames (1 to 10000)")
      ->required()
      ->transform(integer_in(1, kMaxFrames));
  cmd->add_option("--from-altitude", options.from_altitude,
                  "Altitude of the first frame above terrain.base_height (> 0, <= 1e9)")
      ->required();
  cmd->add_option("--to-altitude", options.to_altitude,
                  "Altitude of the last frame above terrain.base_height (> 0, <= 1e9)")
      ->required();
  cmd->add_option("--to-pitch", options.to_pitch_deg,
                  "Pitch of the last frame in degrees (-89 to 89; default -8)");
  add_shard_option(cmd, options.shard, "path's frames");
  return cmd;
}

CameraSettings path_camera(const Scene& scene, const PathOptions& o, int k) {
  const double f = o.frames > 1 ? double(k) / double(o.frames - 1) : 0.0;
  CameraSettings camera = scene.camera;
  // Log-uniform: the same ratio from frame to frame (A, B > 0: validated).
  const double altitude = o.from_altitude * std::pow(o.to_altitude / o.from_altitude, f);
  camera.position[1] = scene.terrain.base_height + altitude;
  const double ease = f * f * (3.0 - 2.0 * f);
  camera.pitch_deg = scene.camera.pitch_deg + (o.to_pitch_deg - scene.camera.pitch_deg) * ease;
  return camera;
}

int run_path_command(const Scene& scene, const PathOptions& o, std::ostream& out,
                     std::ostream& err) {
  const auto bad = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return kExitBadInput;
  };
  if (o.frames < 1 || o.frames > kMaxFrames) {
    return bad("--frames " + std::to_string(o.frames) + " is out of range; allowed 1 to " +
               std::to_string(kMaxFrames));
  }
  for (const auto& [name, value] :
       {std::pair{"--from-altitude", o.from_altitude}, std::pair{"--to-altitude", o.to_altitude}}) {
    if (!(value > 0.0 && value <= limits::kMaxPlanetLength)) {
      return bad(
          std::string(name) + " " + format_number(value) +
          " is out of range; allowed 0 < altitude <= " + format_number(limits::kMaxPlanetLength));
    }
  }
  if (!(o.to_pitch_deg >= kMinPitchDeg && o.to_pitch_deg <= kMaxPitchDeg)) {
    return bad("--to-pitch " + format_number(o.to_pitch_deg) + " is out of range; allowed " +
               format_number(kMinPitchDeg) + " to " + format_number(kMaxPitchDeg));
  }
  if (o.out_dir.empty()) {
    return bad("--out is empty; give a directory name");
  }
  // Every frame's scene is validated before anything is written (SceneError: exit 2).
  std::vector<Scene> frames;
  frames.reserve(std::size_t(o.frames));
  for (int k = 0; k < o.frames; ++k) {
    Scene frame = scene;
    frame.camera = path_camera(scene, o, k);
    validate_scene(frame);
    frames.push_back(std::move(frame));
  }
  // --shard: this shard's frames alone (shard.h); its record names them for relief stitch.
  const std::optional<Shard> shard =
      o.shard.empty() ? std::nullopt : std::optional(parse_shard(o.shard, std::getenv));
  const ShardSpan span = shard ? shard_frames(o.frames, *shard) : ShardSpan{0, o.frames};
  // Frames of an earlier path left in the directory would mix with these (a shorter path keeps
  // the old frames past its last), and one of them being a directory would stop this path
  // half-way: refused before anything is written. The shards of one path may share a
  // directory: each refuses only its own frames and record.
  std::error_code error;
  if (std::filesystem::is_directory(o.out_dir, error)) {
    for (const auto& entry : std::filesystem::directory_iterator(o.out_dir, error)) {
      const std::string name = entry.path().filename().string();
      int k = -1;
      const bool frame = name.starts_with("frame_") && name.ends_with(".png") &&
                         std::sscanf(name.c_str(), "frame_%d.png", &k) == 1;
      // Unsharded: any frame. A shard: its own frames and its own record.
      const bool taken =
          shard ? (frame && k >= span.begin && k < span.end) || name == path_shard_file_name(*shard)
                : frame;
      if (taken) {
        return bad("--out " + o.out_dir + " already holds " + name +
                   " (from an earlier path?); allowed: a new directory, or one without " +
                   (shard ? "this shard's frames and record" : std::string("frame_*.png")));
      }
    }
  }
  FrameRequest request;
  request.backend = o.backend;
  const MemoryEstimate estimate = estimate_render_memory(scene, request.backend, request.outputs);
  check_memory(estimate, o.budget, "each frame of this path", render_memory_advice(scene));
  request.max_bin_bytes = memory_left(estimate, o.budget);
  const SceneResources resources = load_scene_resources(scene);  // the camera's not in them

  OutputDirectory directory(o.out_dir);
  TerminalProgress progress("relief path", "frames");
  for (int k = span.begin; k < span.end; ++k) {
    const Scene& frame_scene = frames[std::size_t(k)];
    char altitude[64];
    std::snprintf(altitude, sizeof altitude, "altitude %.4g",
                  frame_scene.camera.position[1] - scene.terrain.base_height);
    progress.update(k - span.begin, span.end - span.begin, altitude);
    const Frame frame = render_frame(frame_scene, resources, request);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    write_file_atomically(std::filesystem::path(o.out_dir) / name,
                          encode_png_rgb(frame.image.width, frame.image.height, frame.image.srgb,
                                         scene_metadata(frame_scene)));
    directory.keep();
  }
  if (shard) {  // last: a record stands for frames that are all written
    const std::string record = path_shard_record_text(*shard, o.frames);
    write_file_atomically(
        std::filesystem::path(o.out_dir) / path_shard_file_name(*shard),
        std::span(reinterpret_cast<const unsigned char*>(record.data()), record.size()));
  }
  progress.update(span.end - span.begin, span.end - span.begin);
  progress.finish();
  out << "wrote " << span.end - span.begin << " frames to " << o.out_dir << " (altitude "
      << format_number(o.from_altitude) << " to " << format_number(o.to_altitude);
  if (shard) {
    out << "; shard " << shard->index << "/" << shard->count << ": frames " << span.begin << " to "
        << span.end - 1;
  }
  out << ")\n";
  return kExitOk;
}

}  // namespace relief
