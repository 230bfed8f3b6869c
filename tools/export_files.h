// `relief export`'s parts (export_command.h): the options checked into a plan, the memory the
// plan takes, and its files encoded.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/memory_budget.h"
#include "pipeline/terrain_samples.h"
#include "tools/atomic_file.h"
#include "tools/distinct_paths.h"
#include "tools/export_command.h"
#include "tools/float_image_file.h"
#include "tools/height_file.h"
#include "tools/mesh_file.h"

namespace relief {

struct ExportPlan {
  SampleRegion region;
  TerrainSampleRequest request;
  std::optional<HeightFormat> heights;
  std::optional<FloatFormat> float_normals;  // nullopt: an 8-bit PNG (when --normals is given)
  std::optional<MeshFormat> mesh;
  std::vector<std::string> splat_files;  // PREFIX_0.png, ... one per 4 layers
  std::vector<CommandPath> outputs;      // every file the export writes
};

// The plan of a valid request; nullopt after writing the reason to `err` ("relief: error: ..."
// naming the option, the value and what is allowed).
std::optional<ExportPlan> plan_export(const Scene& scene, const ExportOptions& options,
                                      std::ostream& err);

// The samples and the files' encodings, added to `estimate`.
void add_export_memory(const Scene& scene, const ExportOptions& options, const ExportPlan& plan,
                       MemoryEstimate& estimate);

struct ExportFigures {
  std::string summary;  // what the command prints
};

// Encodes every requested file into `outputs` (not committed).
ExportFigures write_export_files(const Scene& scene, const ExportOptions& options,
                                 const ExportPlan& plan, const TerrainSamples& samples,
                                 OutputSet& outputs);

}  // namespace relief
