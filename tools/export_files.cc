#include "tools/export_files.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/png_encoder.h"
#include "pipeline/geotiff_reference.h"
#include "pipeline/heightfield_files.h"
#include "tools/geotiff_file.h"

namespace relief {

namespace {

constexpr int kLayersPerSplat = 4;

std::span<const unsigned char> bytes_of(const std::string& text) {
  return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

// An encoder returns nothing only when it ran out of memory: no empty file written for it.
std::vector<unsigned char> encoded(const std::string& file, std::vector<unsigned char> bytes) {
  if (bytes.empty()) {
    throw OutputError(file + ": the file could not be encoded (out of memory)");
  }
  return bytes;
}

std::uint8_t unit_byte(double v) {  // [-1, 1] to [0, 255]
  return static_cast<std::uint8_t>(std::clamp(std::round((v + 1.0) * 127.5), 0.0, 255.0));
}

}  // namespace

std::optional<ExportPlan> plan_export(const Scene& scene, const ExportOptions& o,
                                      std::ostream& err) {
  const auto bad = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return std::nullopt;
  };
  if (scene.terrain.planet) {
    return bad("relief export samples a terrain on the plane; this scene sets terrain.planet");
  }
  ExportPlan plan;
  auto& rect = plan.region.rect;
  if (!o.region.empty()) {
    std::copy_n(o.region.begin(), 4, rect.begin());
  } else if (const SketchSettings* field = added_height_field(scene.terrain)) {
    rect = field->extent;
    // A GeoTIFF's own placement (a file that cannot be read is refused when it is loaded).
    const std::optional<HeightFieldPeek> peek =
        scene.terrain.heightfield && scene.terrain.heightfield->georeferenced
            ? peek_height_field(*scene.terrain.heightfield)
            : std::nullopt;
    if (peek) {
      rect = georeferenced_extent(*scene.terrain.heightfield, int(peek->width), int(peek->height));
    }
  } else if (scene.terrain.sketch) {
    rect = scene.terrain.sketch->extent;
  } else {
    return bad(
        "--region is required: this scene has no terrain.heightfield or terrain.sketch "
        "whose extent it could default to");
  }
  static constexpr const char* kCorner[] = {"x0", "z0", "x1", "z1"};
  for (int k = 0; k < 4; ++k) {
    if (!(std::abs(rect[k]) <= limits::kMaxCameraCoordinate)) {
      return bad("--region " + std::string(kCorner[k]) + " " + format_number(rect[k]) +
                 " is out of range; allowed -1e12 to 1e12");
    }
  }
  if (!(rect[2] - rect[0] >= limits::kMinSketchSpan &&
        rect[3] - rect[1] >= limits::kMinSketchSpan)) {
    return bad("--region " + format_number(rect[0]) + " " + format_number(rect[1]) + " " +
               format_number(rect[2]) + " " + format_number(rect[3]) +
               " is reversed or narrower than 0.001; allowed x1 - x0 and z1 - z0 >= 0.001 (as "
               "terrain.heightfield.extent, which reads the export back)");
  }
  const std::string range = "2 to " + std::to_string(kMaxExportSize);
  // "N" or "WxH": whole numbers in digits, each 2 to kMaxExportSize.
  const auto side = [&](std::string_view text) -> std::optional<int> {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < 2 ||
        value > kMaxExportSize) {
      return std::nullopt;
    }
    return value;
  };
  const std::size_t x = o.size.find('x');
  const std::optional<int> w = side(std::string_view(o.size).substr(0, x));
  const std::optional<int> h =
      x == std::string::npos ? std::nullopt : side(std::string_view(o.size).substr(x + 1));
  if (!w || (x != std::string::npos && !h)) {
    return bad("--size " + brief_text(o.size) + " is not N or WxH with each side " + range);
  }
  int& width = plan.region.width;
  int& height = plan.region.height;
  width = *w;
  if (h) {
    height = *h;
  } else {
    // Square cells: the z samples in proportion (the spans' ratio, both >= 1e-3, finite).
    const double z = std::round(width * ((rect[3] - rect[1]) / (rect[2] - rect[0])));
    if (!(z >= 2 && z <= kMaxExportSize)) {
      return bad("--size " + std::to_string(width) + " gives square cells " + format_number(z) +
                 " samples along z, out of range (" + range + "); give both: --size WxH");
    }
    height = int(z);
  }
  // Samples must stay distinct in double: a cell at least 2^-40 of the farthest coordinate
  // (4096 of its ulps), so that every sample's position carries 12 bits within its cell.
  const double farthest =
      std::max({std::abs(rect[0]), std::abs(rect[1]), std::abs(rect[2]), std::abs(rect[3])});
  const double cell = std::min((rect[2] - rect[0]) / width, (rect[3] - rect[1]) / height);
  if (!(cell >= std::ldexp(farthest, -40))) {
    return bad("--region and --size give cells of " + format_number(cell) +
               ", too fine for "
               "coordinates near " +
               format_number(farthest) + "; allowed cells of at least " +
               format_number(std::ldexp(farthest, -40)) +
               " there (fewer samples, or a region "
               "nearer the origin)");
  }
  if (!o.heights.empty()) {
    plan.heights = height_format(o.heights);
    if (!plan.heights) {
      return bad("-o " + brief_text(o.heights) +
                 ": give a file name ending in .png (16-bit grey), .r16, .pfm, .exr or .tif "
                 "(GeoTIFF)");
    }
    plan.outputs.push_back({"-o", o.heights});
  }
  if (!o.normals.empty()) {
    plan.float_normals = float_format_of(o.normals);
    if (!plan.float_normals && !has_extension(o.normals, ".png")) {
      return bad("--normals " + brief_text(o.normals) +
                 ": give a file name ending in .png (8 bits), .pfm or .exr (floats)");
    }
    plan.outputs.push_back({"--normals", o.normals});
    plan.request.normals = true;
  }
  if (!o.splat.empty()) {
    const std::string file = std::filesystem::path(o.splat).filename().string();
    if (file.empty() || file == "." || file == "..") {
      return bad("--splat " + brief_text(o.splat) +
                 " has no file name part; give a prefix such as out/splat");
    }
    const int layers = int(scene.shading.layers.size());  // 1 to 8: validate_scene
    for (int g = 0; g * kLayersPerSplat < layers; ++g) {
      plan.splat_files.push_back(o.splat + "_" + std::to_string(g) + ".png");
      plan.outputs.push_back({"--splat", plan.splat_files.back()});
    }
    plan.request.weights = true;
  }
  if (!o.mesh.empty()) {
    plan.mesh = mesh_format(o.mesh);
    if (!plan.mesh) {
      return bad("--mesh " + brief_text(o.mesh) + ": give a file name ending in .obj or .glb");
    }
    if (width > kMaxExportMeshSize || height > kMaxExportMeshSize) {
      return bad("--mesh: --size " + std::to_string(width) + " x " + std::to_string(height) +
                 " is too large for a mesh; allowed at most " + std::to_string(kMaxExportMeshSize) +
                 " samples a side");
    }
    plan.outputs.push_back({"--mesh", o.mesh});
    plan.request.normals = true;
  }
  if (plan.outputs.empty()) {
    return bad("nothing to export; give -o (heights), --normals, --splat or --mesh");
  }
  if (!o.scene_out.empty()) {
    if (o.heights.empty()) {
      return bad("--scene-out needs -o: the scene renders the exported height map");
    }
    if (!is_valid_utf8(o.heights) || !is_valid_utf8(o.scene_out)) {
      return bad(
          "--scene-out: the scene names the height map in JSON, which holds UTF-8 text "
          "only; give -o and --scene-out names in UTF-8");
    }
    plan.outputs.push_back({"--scene-out", o.scene_out});
  }
  if (!o.json.empty()) {
    plan.outputs.push_back({"--json", o.json});
  }
  return plan;
}

void add_export_memory(const Scene& scene, const ExportOptions& o, const ExportPlan& plan,
                       MemoryEstimate& estimate) {
  const SampleRegion& r = plan.region;
  const std::uintmax_t samples = std::uintmax_t(r.width) * std::uintmax_t(r.height);
  estimate.add("the samples", terrain_samples_bytes(scene, r, plan.request));
  if (plan.heights) {
    estimate.add("the height map's encoding", 12 * samples);
  }
  if (!o.normals.empty()) {
    estimate.add("the normal map's encoding", (plan.float_normals ? 24 : 10) * samples);
  }
  if (!plan.splat_files.empty()) {
    estimate.add("a splat map's encoding", 12 * samples);
  }
  if (plan.mesh) {
    estimate.add("the mesh's encoding", 2 * mesh_file_bytes(*plan.mesh, r.width, r.height));
  }
}

ExportFigures write_export_files(const Scene& scene, const ExportOptions& o, const ExportPlan& plan,
                                 const TerrainSamples& samples, OutputSet& outputs) {
  const SampleRegion& r = plan.region;
  const int w = r.width, h = r.height;
  const std::size_t count = std::size_t(w) * std::size_t(h);
  const double low = samples.low + 0.0, high = samples.high + 0.0;  // -0 as 0
  // Levels 0 and 65535 stand for the samples' extremes; a flat map's levels are all 0, its
  // range one unit wide (terrain.heightfield needs lo < hi). A terrain that is a height field
  // alone keeps its own range (base_height + terrain.heightfield.height) where every sample
  // lies within it (to half a level): exported at its own samples it then gives back its levels,
  // and the exported scene the same field bit for bit (docs/export.md).
  const bool levels = plan.heights && holds_levels(*plan.heights);
  const SketchSettings* source = added_height_field(scene.terrain);
  const bool field_alone = source != nullptr && !fractal_enabled(scene.terrain);
  double level_low = low, level_high = high > low ? high : low + 1.0;
  double base = 0.0;
  Vec2d field_range = {level_low, level_high};
  // Within half a level beyond either end: those samples round to level 0 or 65535 anyway.
  const double half_level =
      field_alone ? 0.5 * (source->height[1] - source->height[0]) / 65535.0 : 0.0;
  if (field_alone && low >= scene.terrain.base_height + source->height[0] - half_level &&
      high <= scene.terrain.base_height + source->height[1] + half_level) {
    base = scene.terrain.base_height;
    field_range = source->height;
    level_low = base + field_range[0];
    level_high = base + field_range[1];
  }
  nlohmann::ordered_json figures = {
      {"region", r.rect},
      {"samples", {w, h}},
      {"cell", {(r.rect[2] - r.rect[0]) / w, (r.rect[3] - r.rect[1]) / h}},
      {"low", low},
      {"high", high}};
  if (levels) {
    figures["levels"] = {{"0", level_low}, {"65535", level_high}};
  }
  if (plan.heights) {
    const std::vector<ImageText> text = {{"relief:heights", figures.dump()}};
    outputs.add(o.heights,
                encoded(o.heights, *plan.heights == HeightFormat::kGeoTiff
                                       ? encode_geotiff(w, h, samples.heights, r.rect)
                                       : encode_heights(*plan.heights, w, h, samples.heights,
                                                        level_low, level_high, text)));
  }
  if (!o.normals.empty()) {
    if (plan.float_normals) {  // rows bottom first: z = h - 1 first
      std::vector<float> rows(3 * count);
      for (int z = 0; z < h; ++z) {
        std::copy_n(samples.normals.begin() + std::ptrdiff_t(3 * std::size_t(z) * w), 3 * w,
                    rows.begin() + std::ptrdiff_t(3 * std::size_t(h - 1 - z) * w));
      }
      outputs.add(o.normals, encoded(o.normals, encode_float_image(*plan.float_normals, w, h, 3,
                                                                   rows, 3 * std::size_t(w), {})));
    } else {
      // Seen from above with z0 at the top: R = n_x, G = -n_z (the picture's up), B = n_y.
      std::vector<std::uint8_t> rgb(3 * count);
      for (int z = 0; z < h; ++z) {
        for (int x = 0; x < w; ++x) {
          const std::size_t k = std::size_t(z) * w + x;
          const std::size_t p = 3 * (std::size_t(h - 1 - z) * w + x);  // row 0 = the bottom
          rgb[p] = unit_byte(samples.normals[3 * k]);
          rgb[p + 1] = unit_byte(-double(samples.normals[3 * k + 2]));
          rgb[p + 2] = unit_byte(samples.normals[3 * k + 1]);
        }
      }
      outputs.add(o.normals, encoded(o.normals, encode_png_rgb(w, h, rgb)));
    }
  }
  for (std::size_t g = 0; g < plan.splat_files.size(); ++g) {
    std::vector<std::uint8_t> rgba(4 * count, 0);
    const int first = int(g) * kLayersPerSplat;
    const int n = std::min(kLayersPerSplat, samples.layers - first);
    for (std::size_t k = 0; k < count; ++k) {
      for (int c = 0; c < n; ++c) {
        rgba[4 * k + std::size_t(c)] = samples.weights[std::size_t(samples.layers) * k + first + c];
      }
    }
    outputs.add(plan.splat_files[g], encoded(plan.splat_files[g], encode_png_rgba8(w, h, rgba)));
  }
  if (plan.mesh) {
    outputs.add(
        o.mesh,
        encoded(o.mesh, encode_mesh(*plan.mesh, {w, h, r.rect, samples.heights, samples.normals})));
  }
  if (!o.scene_out.empty()) {
    // The exported map as the terrain, its samples interpolated (they are point heights), with
    // nothing added: no base height, no fractal.
    Scene round_trip = scene;
    HeightFieldSettings field;
    // Relative to the scene's directory (the pair moves together), unless that directory is
    // reached through a link: a scene's relative paths are joined to the directory as it is
    // spelled, so the map's real path then, which every spelling finds.
    const std::filesystem::path spelled =
        std::filesystem::absolute(o.scene_out).lexically_normal().parent_path();
    // The scene's real directory: its file may itself be a link (written through).
    const std::filesystem::path real =
        std::filesystem::weakly_canonical(std::filesystem::absolute(o.scene_out)).parent_path();
    const std::filesystem::path map =
        std::filesystem::weakly_canonical(std::filesystem::absolute(o.heights));
    field.image = (real == spelled ? map.lexically_proximate(real) : map).generic_string();
    field.extent = r.rect;  // a GeoTIFF's own placement gives it again
    field.georeferenced = *plan.heights == HeightFormat::kGeoTiff;
    field.height = levels ? field_range : Vec2d{0.0, 1.0};
    field.raw_width = *plan.heights == HeightFormat::kRaw16 && w != h ? w : 0;
    field.interpolating = true;
    // A height field keeps its own choice; the fractal's samples are read filtered to the
    // grid's spacing, as the fractal's octaves were (closer to the source's frame, measured in
    // docs/export.md).
    field.level_of_detail =
        field_alone ? scene.terrain.heightfield && scene.terrain.heightfield->level_of_detail
                    : true;
    // A height field holds world heights within +-1e7 (its loader's rule): checked here, before
    // anything is written, rather than when the scene is read back.
    const double reach = std::max(std::abs(low), std::abs(high));
    if (!(reach <= limits::kMaxBaseHeight)) {
      throw SceneError("--scene-out", "--scene-out: the exported heights reach " +
                                          format_number(reach) +
                                          ", beyond the +-1e7 a height field holds; nothing was "
                                          "written (export without --scene-out)");
    }
    // A gradient over the terrain's height bounds keeps the source's bounds: the exported
    // field's own would move every stop.
    GradientSettings& gradient = round_trip.shading.gradient;
    if (round_trip.shading.mode == ShadingMode::kGradient && !gradient.range &&
        samples.bound_low < samples.bound_high) {
      if (!(std::max(std::abs(samples.bound_low), std::abs(samples.bound_high)) <=
            limits::kMaxBaseHeight)) {
        throw SceneError("--scene-out",
                         "--scene-out: the gradient spans the terrain's height bounds [" +
                             format_number(samples.bound_low) + ", " +
                             format_number(samples.bound_high) +
                             "], beyond the +-1e7 shading.gradient.range holds; nothing was "
                             "written (set shading.gradient.range)");
      }
      gradient.range = Vec2d{samples.bound_low, samples.bound_high};
    }
    round_trip.terrain.sketch.reset();
    round_trip.terrain.heightfield = field;
    round_trip.terrain.base_height = (levels ? base : 0.0) + 0.0;  // -0 as 0
    validate_scene(round_trip);
    const std::string text = scene_json_text(round_trip);
    outputs.add(o.scene_out, bytes_of(text));
  }
  std::string json_text;
  if (!o.json.empty()) {
    json_text = figures.dump(2) + "\n";
    outputs.add(o.json, bytes_of(json_text));
  }
  std::ostringstream summary;
  summary << "exported " << w << "x" << h << " samples over [" << format_number(r.rect[0] + 0.0)
          << ", " << format_number(r.rect[2] + 0.0) << "] x [" << format_number(r.rect[1] + 0.0)
          << ", " << format_number(r.rect[3] + 0.0) << "]: heights " << format_number(low) << " to "
          << format_number(high) << "\n";
  for (const CommandPath& path : plan.outputs) {
    summary << "wrote " << path.path.string() << "\n";
  }
  return {summary.str()};
}

}  // namespace relief
