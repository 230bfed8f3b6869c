#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "core/scene/json_input.h"
#include "image/crc32.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/distinct_paths.h"
#include "tools/float_image_file.h"
#include "tools/render_report.h"
#include "tools/shard.h"

namespace relief {

namespace {

std::span<const unsigned char> bytes_of(const std::vector<std::uint32_t>& values) {
  return {reinterpret_cast<const unsigned char*>(values.data()), values.size() * 4};
}

}  // namespace

void print_scene_notes(const std::vector<std::string>& notes, std::ostream& err) {
  for (const std::string& note : notes) {
    err << "relief: note: " << note << "\n";
  }
}

int check_render_paths(const Scene& scene, const std::string& scene_arg,
                       const RenderOptions& options, std::ostream& err) {
  const std::string& o = options.output;
  if (!o.empty() && !has_extension(o, ".png")) {
    err << "relief: error: -o " << brief_text(o)
        << ": the image is written as PNG; give a file name ending in .png\n";
    return kExitBadInput;
  }
  const std::vector<std::tuple<const char*, const std::string*, const char*>> extras = {
      {"--float", &options.float_output, ".pfm or .exr"},
      {"--depth", &options.depth_output, ".pfm or .exr"},
      {"--primitive", &options.primitive_output, ".bin"},
      {"--normal", &options.normal_output, ".pfm or .exr"},
      {"--height", &options.height_output, ".pfm or .exr"},
      {"--octaves", &options.octaves_output, ".pfm or .exr"}};
  for (const auto& [name, value, extension] : extras) {
    const bool floats = std::string_view(extension) != ".bin";
    if (!value->empty() &&
        !(floats ? float_format_of(*value).has_value() : has_extension(*value, extension))) {
      err << "relief: error: " << name << " " << brief_text(*value) << ": give a file name "
          << "ending in " << extension << "\n";
      return kExitBadInput;
    }
  }
  // Every file the render reads or writes, the scene's default outputs included.
  std::vector<CommandPath> paths = scene_input_paths(scene_arg, scene);
  paths.push_back({o.empty() ? "output.image" : "-o", o.empty() ? scene.output.image : o});
  paths.push_back({options.float_output.empty() ? "output.float_image" : "--float",
                   options.float_output.empty() ? scene.output.float_image.value_or("")
                                                : options.float_output});
  for (std::size_t k = 1; k < extras.size(); ++k) {
    paths.push_back({std::get<0>(extras[k]), *std::get<1>(extras[k])});
  }
  paths.push_back({"--stats-json", options.stats_json});
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    err << "relief: error: " << *conflict << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

int run_render_command(const Scene& scene, const RenderOptions& options, std::ostream& out,
                       std::ostream& err) {
  const std::string path = options.output.empty() ? scene.output.image : options.output;
  const std::string float_path =
      options.float_output.empty() ? scene.output.float_image.value_or("") : options.float_output;
  FrameRequest request;
  request.backend = options.backend;
  request.outputs.linear = !float_path.empty();
  request.outputs.depth = !options.depth_output.empty();
  request.outputs.primitive = !options.primitive_output.empty();
  request.outputs.normal = !options.normal_output.empty();
  request.outputs.world_height = !options.height_output.empty();
  request.outputs.octaves = !options.octaves_output.empty();
  // --shard: a band of whole tile rows of the image (shard.h), every requested output of it.
  std::optional<Shard> shard;
  std::optional<ShardSpan> band;
  if (!options.shard.empty()) {
    shard = parse_shard(options.shard, std::getenv);
    band = shard_rows(scene.viewport.height, *shard);
  }
  const MemoryEstimate estimate =
      band ? estimate_rows_render_memory(scene, request.backend, request.outputs,
                                         band->end - band->begin)
           : estimate_render_memory(scene, request.backend, request.outputs);
  check_memory(estimate, options.budget, "this render", render_memory_advice(scene));
  request.max_bin_bytes = memory_left(estimate, options.budget);

  const auto setup_start = std::chrono::steady_clock::now();
  // Validates the files it reads (a gradient reads no layer texture).
  const SceneResources resources = load_scene_resources(scene);
  print_scene_notes(resources.notes, err);
  const double setup_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - setup_start)
          .count();
  Frame frame;
  RenderRuns runs;
  runs.setup_ms = setup_ms;
  for (int run = 0; run < options.repeat; ++run) {
    frame = band
                ? render_frame_rows(scene, resources, request, band->begin, band->end - band->begin)
                : render_frame(scene, resources, request);
    runs.add(frame.stats);
  }

  const FrameImage& image = frame.image;
  const std::size_t row = std::size_t(image.width);
  // Every image carries the scene that made it (image/image_metadata.h).
  const std::vector<ImageText> metadata = scene_metadata(scene);
  const auto floats = [&](const std::string& name, int channels, std::span<const float> values) {
    return encode_float_image(float_format_of(name).value_or(FloatFormat::kPfm), image.width,
                              image.height, channels, values, row * std::size_t(channels),
                              metadata);
  };
  // The extra outputs first: a shard's PNG names each with its size and CRC (shard.h).
  std::vector<std::pair<std::string, std::vector<unsigned char>>> extras;
  std::vector<ShardCompanion> companions;
  const auto extra = [&](std::string_view kind, const std::string& file,
                         std::vector<unsigned char> bytes) {
    if (shard) {
      companions.push_back(
          {std::string(kind), companion_file_name(path, file), bytes.size(), crc32(bytes)});
    }
    extras.emplace_back(file, std::move(bytes));
  };
  if (!float_path.empty()) {
    extra("float", float_path, floats(float_path, 3, image.linear));
  }
  if (request.outputs.depth) {
    extra("depth", options.depth_output, floats(options.depth_output, 1, image.depth));
  }
  if (request.outputs.normal) {
    extra("normal", options.normal_output, floats(options.normal_output, 3, image.normal));
  }
  if (request.outputs.world_height) {
    extra("height", options.height_output, floats(options.height_output, 1, image.world_height));
  }
  if (request.outputs.octaves) {
    extra("octaves", options.octaves_output, floats(options.octaves_output, 1, image.octaves));
  }
  if (request.outputs.primitive) {
    const std::span<const unsigned char> ids = bytes_of(image.primitive);
    extra("primitive", options.primitive_output, {ids.begin(), ids.end()});
  }
  std::vector<ImageText> png_text = metadata;
  if (band) {
    const int height = scene.viewport.height;
    png_text.push_back({std::string(kShardKey),
                        shard_record_text({*shard, std::string(backend_name(request.backend)),
                                           image.width, height, height - band->end,
                                           band->end - band->begin, kImageShardUnit, companions})});
  }
  OutputSet files;  // every requested file appears, or none does
  files.add(path, encode_png_rgb(image.width, image.height, image.srgb, png_text));
  for (const auto& [file, bytes] : extras) {
    files.add(file, bytes);
  }
  std::string stats_text;
  if (!options.stats_json.empty()) {
    stats_text = stage_stats_json(scene, request.backend, runs).dump(2) + "\n";
    files.add(options.stats_json,
              std::span<const unsigned char>(
                  reinterpret_cast<const unsigned char*>(stats_text.data()), stats_text.size()));
  }
  files.commit();

  out << std::fixed << std::setprecision(3) << image.width << "x" << image.height << " image, "
      << scene.grid.width << "x" << scene.grid.height << " grid, backend "
      << backend_label(request.backend) << ", median of " << options.repeat << " run(s):\n";
  if (options.stats) {
    print_stage_stats(out, runs);
  } else {
    print_stage_times(out, runs);
  }
  const raster::RasterStats& s = frame.stats.raster;
  out << "  scene set-up (lattice, textures, mip chains) " << setup_ms << " ms, once\n"
      << "  triangles submitted " << s.triangles
      << (request.backend == Backend::kGl ? " (to GL's rasteriser)"
                                          : ", set up " + std::to_string(s.setup))
      << "\n"
      << "wrote " << path << (float_path.empty() ? "" : " and " + float_path) << "\n";
  return kExitOk;
}

}  // namespace relief
