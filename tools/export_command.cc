#include "tools/export_command.h"

#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/png_encoder.h"
#include "pipeline/job_memory.h"
#include "pipeline/terrain_samples.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/distinct_paths.h"
#include "tools/export_files.h"
#include "tools/height_file.h"
#include "tools/image_library.h"
#include "tools/mesh_file.h"
#include "tools/terminal_progress.h"

namespace relief {

CLI::App* add_export_command(CLI::App& app, ExportOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export the terrain over a world rectangle: the height map (16-bit PNG, RAW16, PFM, EXR, "
      "GeoTIFF), "
      "the normal map, the layer weights as splat maps, a mesh (OBJ or glTF .glb) and a scene "
      "that renders the exported heights");
  cmd->add_option("--region", o.region,
                  "x0 z0 x1 z1, the world rectangle (default: the scene's height field or sketch "
                  "extent); samples sit at the centres of a grid of cells over it")
      ->expected(4)
      ->check(kNonEmptyNumber);
  cmd->add_option("--size", o.size,
                  "Samples along x (N: z from square cells) or along both (WxH), each 2 to " +
                      std::to_string(kMaxExportSize))
      ->required();
  const std::vector<std::tuple<const char*, std::string*, const char*>> files = {
      {"-o,--heights", &o.heights,
       "The height map: .png (16 bits), .r16, .pfm, .exr or .tif (GeoTIFF, placed by its tags)"},
      {"--normals", &o.normals, "The normal map: .png (8-bit RGB) or .pfm/.exr (float)"},
      {"--splat", &o.splat,
       "Splat maps PREFIX_0.png, PREFIX_1.png: layers 0-3 and 4-7 as RGBA bytes summing to 255"},
      {"--mesh", &o.mesh, "The mesh: .obj or .glb (binary glTF 2.0)"},
      {"--scene-out", &o.scene_out,
       "A scene rendering the exported height map (terrain.heightfield, interpolating)"},
      {"--json", &o.json, "The figures (region, samples, height range) as JSON"}};
  for (const auto& [name, value, help] : files) {
    o.file_options.push_back(cmd->add_option(name, *value, help));
  }
  return cmd;
}

int run_export_command(const Scene& scene, const ExportOptions& o, std::ostream& out,
                       std::ostream& err) {
  const auto bad = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return kExitBadInput;
  };
  for (const CLI::Option* option : o.file_options) {
    if (given_empty(option, option->as<std::string>())) {
      return bad(option->get_name() + " is empty; give a file name");
    }
  }
  const std::optional<ExportPlan> plan = plan_export(scene, o, err);
  if (!plan) {
    return kExitBadInput;
  }
  // Every file read or written distinct (links followed), and each output's directory there,
  // before any work: nothing is written when one of them is wrong.
  std::vector<CommandPath> paths = scene_input_paths(o.scene_arg, scene);
  for (const CommandPath& path : plan->outputs) {
    paths.push_back(path);
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    return bad(*conflict);
  }
  for (const CommandPath& path : plan->outputs) {
    if (const std::optional<std::string> problem = output_path_problem(path.path)) {
      return bad(path.option + " " + *problem);
    }
  }
  MemoryEstimate estimate = estimate_scene_resources_memory(scene);
  add_export_memory(scene, o, *plan, estimate);
  check_memory(estimate, o.budget, "this export", "Lower --size, or export fewer files");
  // An EXR is written through the OpenImageIO module: loaded now, so that a process that
  // cannot load it is refused before the work, not after it.
  if (plan->heights == HeightFormat::kExr || plan->float_normals == FloatFormat::kExr) {
    image_library();
  }
  const SceneResources resources = load_scene_resources(scene);

  TerminalProgress progress("relief export", "rows");
  const TerrainSamples samples =
      sample_terrain(scene, resources, plan->region, plan->request,
                     [&](int done, int total) { progress.update(done, total); });
  progress.finish();
  OutputSet outputs;
  const ExportFigures figures = write_export_files(scene, o, *plan, samples, outputs);
  outputs.commit();
  out << figures.summary;
  return kExitOk;
}

}  // namespace relief
