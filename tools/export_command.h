// `relief export [SCENE] --region x0 z0 x1 z1 --size N ...` (export_command.cc, docs/export.md):
// the terrain of any scene over a world rectangle as files other tools read: the height map
// (16-bit PNG, RAW16, PFM, EXR, GeoTIFF), the normal map, the layer weights as splat maps (8-bit
// RGBA PNG per 4 layers), a mesh (OBJ or binary glTF), and a scene that renders the exported map
// with terrain.heightfield.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/memory_budget.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

inline constexpr int kMaxExportSize = 16385;     // samples a side, as terrain.heightfield's
inline constexpr int kMaxExportMeshSize = 4097;  // a mesh's samples a side

struct ExportOptions {
  std::vector<double> region;  // x0 z0 x1 z1; empty: the scene's height field or sketch extent
  std::string size;            // "N" (along x; z from square cells) or "WxH"
  std::string heights;         // .png (16-bit), .r16/.raw, .pfm, .exr or .tif/.tiff
  std::string normals;         // .png (8-bit RGB) or .pfm/.exr (3 float channels)
  std::string splat;           // PREFIX: PREFIX_0.png holds layers 0-3, PREFIX_1.png 4-7
  std::string mesh;            // .obj or .glb
  std::string scene_out;       // a scene rendering the exported heights (.json)
  std::string json;            // the figures
  std::vector<const CLI::Option*> file_options;  // to tell an empty name given from none
  std::string scene_arg;                         // SCENE as given: a file is an input
  MemoryBudget budget;
};

// Adds the command and its own options (SCENE, --set, --threads, --max-memory: cli.cc).
CLI::App* add_export_command(CLI::App& app, ExportOptions& options);

// Returns an exit code: 0, or 2 for bad options (nothing written). Throws MemoryLimitError
// when the samples and files do not fit options.budget, OutputError when a file cannot be
// written.
int run_export_command(const Scene& scene, const ExportOptions& options, std::ostream& out,
                       std::ostream& err);

}  // namespace relief
