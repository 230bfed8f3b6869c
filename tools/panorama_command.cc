#include "tools/panorama_command.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/job_memory.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/distinct_paths.h"
#include "tools/panorama.h"
#include "tools/terminal_progress.h"

namespace relief {

CLI::App* add_panorama_command(CLI::App& app, PanoramaOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "panorama",
      "Renders the scene all around its camera as an equirectangular PNG (longitude -180 to 180 "
      "around the camera's yaw, latitude -90 to 90), resampled from a cube of six views, and "
      "measures the seams between the views");
  cmd->add_option("-o,--out", o.output, "The panorama, a .png file")->required();
  cmd->add_option("--width", o.width,
                  "Width in pixels, even, " + std::to_string(kMinPanoramaWidth) + " to " +
                      std::to_string(kMaxPanoramaWidth) + "; the height is half")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  o.json_option = cmd->add_option("--json", o.json, "Also write the seams' figures as JSON");
  return cmd;
}

int run_panorama_command(const Scene& scene, const PanoramaOptions& o, std::ostream& out,
                         std::ostream& err) {
  const auto bad = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return kExitBadInput;
  };
  if (o.width < kMinPanoramaWidth || o.width > kMaxPanoramaWidth || o.width % 2 != 0) {
    return bad("--width " + std::to_string(o.width) + " is out of range; allowed an even width " +
               std::to_string(kMinPanoramaWidth) + " to " + std::to_string(kMaxPanoramaWidth));
  }
  if (o.output.empty() || !has_extension(o.output, ".png")) {
    return bad("-o " + brief_text(o.output) +
               ": the panorama is written as PNG; give a file "
               "name ending in .png");
  }
  if (given_empty(o.json_option, o.json)) {
    return bad("--json is empty; give a file name");
  }
  // Every file read or written distinct (links followed), and each output's directory there,
  // before any work: nothing is written when one of them is wrong.
  std::vector<CommandPath> paths = scene_input_paths(o.scene_arg, scene);
  paths.push_back({"-o", o.output});
  paths.push_back({"--json", o.json});
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    return bad(*conflict);
  }
  for (const auto& [name, file] : {std::pair{"-o", &o.output}, std::pair{"--json", &o.json}}) {
    const std::filesystem::path parent = std::filesystem::path(*file).parent_path();
    std::error_code error;
    if (!file->empty() && ((!parent.empty() && !std::filesystem::is_directory(parent, error)) ||
                           std::filesystem::is_directory(*file, error))) {
      return bad(std::string(name) + " " + brief_text(*file) +
                 ": its directory does not exist or it is a directory; give a file in an "
                 "existing directory");
    }
  }
  // Each view spans 90 degrees in side - 2 margin pixels: at the equator a quarter of the
  // panorama's width, as many pixels as the panorama has there.
  const int side = o.width / 4 + 2 * kPanoramaFaceMargin;
  const PanoramaViews views = panorama_views(scene.camera, side);
  std::vector<Scene> view_scenes;
  for (const CameraSettings& camera : views.cameras) {
    Scene view = scene;
    view.camera = camera;
    view.viewport = views.viewport;
    validate_scene(view);  // every view before anything is rendered (SceneError: exit 2)
    view_scenes.push_back(std::move(view));
  }
  FrameRequest request;
  request.backend = o.backend;
  request.outputs.linear = true;
  MemoryEstimate estimate = estimate_render_memory(view_scenes.front(), o.backend, request.outputs);
  estimate.add("six views' linear radiance",
               6 * std::uintmax_t(side) * std::uintmax_t(side) * 3 * sizeof(float));
  estimate.add("panorama " + std::to_string(o.width) + "x" + std::to_string(o.width / 2),
               std::uintmax_t(o.width) * std::uintmax_t(o.width / 2) * (3 + 13));
  check_memory(estimate, o.budget, "this panorama",
               "Use a smaller --width, or a scene that needs less memory");
  request.max_bin_bytes = memory_left(estimate, o.budget);
  const SceneResources resources = load_scene_resources(scene);  // the camera's not in them

  static constexpr const char* kNames[] = {"front", "right", "back", "left", "up", "down"};
  std::vector<PanoramaFace> faces;
  TerminalProgress progress("relief panorama", "views");
  for (std::size_t k = 0; k < view_scenes.size(); ++k) {
    progress.update(int(k), int(view_scenes.size()), kNames[k]);
    Frame frame = render_frame(view_scenes[k], resources, request);
    faces.push_back({make_camera_frame(view_scenes[k].camera, views.viewport), side,
                     std::move(frame.image.linear)});
  }
  progress.update(int(faces.size()), int(faces.size()), "resampling");
  const Panorama panorama = resample_panorama(faces, scene.camera.yaw_deg, o.width);
  progress.finish();
  // Both files or neither (atomic_file.h).
  OutputSet outputs;
  outputs.add(o.output, encode_png_rgb(panorama.width, panorama.height, panorama.srgb,
                                       scene_metadata(scene)));
  const PanoramaSeams& s = panorama.seams;
  if (!o.json.empty()) {
    const nlohmann::json figures = {{"width", panorama.width},
                                    {"height", panorama.height},
                                    {"view_side", side},
                                    {"seam_directions", s.directions},
                                    {"seam_mean_codes", s.mean_codes},
                                    {"seam_max_codes", s.max_codes}};
    const std::string text = figures.dump(2) + "\n";
    outputs.add(o.json,
                std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
  }
  outputs.commit();
  char line[200];
  std::snprintf(line, sizeof line,
                "seams: %llu directions seen by two views (next to a cube edge), mean "
                "difference %.3f sRGB codes, largest %d\n",
                static_cast<unsigned long long>(s.directions), s.mean_codes, s.max_codes);
  out << line << "wrote " << o.output << " (" << panorama.width << "x" << panorama.height
      << ", six views of " << side << "x" << side << ")\n";
  return kExitOk;
}

}  // namespace relief
