#include "pipeline/frame.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/limits.h"
#include "pipeline/cpu_backend.h"
#include "pipeline/gl_backend.h"
#include "pipeline/stage_table.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Walks the stage table up to and including `last`: each stage's units in fixed chunks of its
// grain (simple_partitioner: the chunks never depend on the thread count), a stage starting
// when the previous one has finished.
void run_table(FrameBackend& backend, StageId last, std::vector<StageTime>& times) {
  for (const StageInfo& stage : kFrameStages) {
    const Clock::time_point start = Clock::now();
    backend.prepare(stage.id);
    const std::size_t units = backend.units(stage.id);
    if (units > 0) {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, units, stage.grain),
          [&](const tbb::blocked_range<std::size_t>& r) {
            backend.run(stage.id, r.begin(), r.end());
          },
          tbb::simple_partitioner());
    }
    backend.after(stage.id);
    StageTime time{std::string(stage.name), milliseconds_since(start), units > 0, {}};
    backend.describe(stage.id, time);
    times.push_back(std::move(time));
    if (stage.id == last) {
      return;
    }
  }
}

// terrain.heightfield.geomipmap's lattice and tiles where the scene draws them (a scene changed
// after loading, the ground truth's among them, may not).
// Refused rather than drawn as the projected grid, or with another scene's tiles, without a word.
const FieldMesh* drawn_field_mesh(const Scene& scene, const SceneResources& resources) {
  const bool drawn = scene.terrain.heightfield && scene.terrain.heightfield->geomipmap;
  if (!drawn) {
    return nullptr;
  }
  const FieldMesh* mesh = resources.field_mesh_or_null();
  if (mesh == nullptr || mesh->map.tile_cells != scene.terrain.heightfield->geomipmap->tile_cells) {
    throw std::invalid_argument(
        "terrain.heightfield.geomipmap: the scene's resources hold no field mesh of its "
        "tile_cells; load them for this scene (load_scene_resources)");
  }
  return mesh;
}

template <class Real>
Frame render_with(const Scene& scene, const SceneResources& resources,
                  const FrameRequest& request) {
  const Clock::time_point start = Clock::now();
  if (request.cloud_steps < 1 || request.cloud_steps > limits::kMaxCloudSteps) {
    throw std::invalid_argument(
        "FrameRequest::cloud_steps = " + std::to_string(request.cloud_steps) + "; allowed 1 ... " +
        std::to_string(limits::kMaxCloudSteps));
  }
  std::unique_ptr<FrameBackend> backend;
  if (request.backend == Backend::kGl) {
    backend = make_gl_backend(scene, resources, request);
  } else {
    backend = std::make_unique<CpuBackend<Real>>(
        scene, resources.lattice, resources.textures, request, resources.sketch_or_null(),
        resources.basis_or_null(), resources.skybox_or_null(), drawn_field_mesh(scene, resources));
  }
  Frame frame;
  frame.stats.stages.push_back({"frame plan", milliseconds_since(start), true, {}});
  run_table(*backend, StageId::kTiles, frame.stats.stages);
  backend->finish(frame);
  frame.stats.total_ms = milliseconds_since(start);
  return frame;
}

}  // namespace

std::string_view backend_name(Backend backend) {
  switch (backend) {
    case Backend::kReference:
      return "reference";
    case Backend::kReferenceDouble:
      return "reference-double";
    case Backend::kSimd:
      return "simd";
    case Backend::kGl:
      return "gl";
  }
  return "reference";
}

std::optional<Backend> backend_from_name(std::string_view name) {
  for (Backend b : {Backend::kReference, Backend::kReferenceDouble, Backend::kSimd, Backend::kGl}) {
    if (backend_name(b) == name) {
      return b;
    }
  }
  return std::nullopt;
}

std::vector<std::string_view> backend_names() {
  return {backend_name(Backend::kReference), backend_name(Backend::kReferenceDouble),
          backend_name(Backend::kSimd), backend_name(Backend::kGl)};
}

Frame render_frame(const Scene& scene, const SceneResources& resources,
                   const FrameRequest& request) {
  return request.backend == Backend::kReferenceDouble
             ? render_with<double>(scene, resources, request)
             : render_with<float>(scene, resources, request);
}

namespace {

// The bands of framebuffer rows [row_begin, row_end), band_rows each (a multiple of the tile
// size; the last band may end at the viewport's top).
template <class Real>
FrameStats render_bands_with(const Scene& scene, const SceneResources& resources,
                             const FrameRequest& request, int band_rows, int row_begin, int row_end,
                             const std::function<void(const FrameImage&, int)>& consume) {
  const Clock::time_point start = Clock::now();
  CpuBackend<Real> backend(scene, resources.lattice, resources.textures, request,
                           resources.sketch_or_null(), resources.basis_or_null(),
                           resources.skybox_or_null(), drawn_field_mesh(scene, resources));
  FrameStats stats;
  stats.stages.push_back({"frame plan", milliseconds_since(start), true, {}});
  run_table(backend, StageId::kBinning, stats.stages);
  const StageInfo& tiles = kFrameStages[std::size(kFrameStages) - 1];
  const Clock::time_point tiles_start = Clock::now();
  for (int first_row = row_begin; first_row < row_end; first_row += band_rows) {
    // The last band ends at row_end, rounded up to whole tiles (row_end is a multiple of the
    // tile size or the viewport's top, where the backend stops).
    const int tile = raster::kTileSize;
    backend.set_band(first_row,
                     std::min(band_rows, (row_end - first_row + tile - 1) / tile * tile));
    backend.prepare(StageId::kTiles);
    const std::size_t units = backend.units(StageId::kTiles);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, units, tiles.grain),
        [&](const tbb::blocked_range<std::size_t>& r) {
          backend.run(StageId::kTiles, r.begin(), r.end());
        },
        tbb::simple_partitioner());
    backend.after(StageId::kTiles);
    Frame band;
    backend.finish(band);
    consume(band.image, first_row);
    stats.tile_parts = std::move(band.stats.tile_parts);
    stats.raster = band.stats.raster;
  }
  StageTime time{std::string(tiles.name), milliseconds_since(tiles_start), true, {}};
  backend.describe(StageId::kTiles, time);
  stats.stages.push_back(std::move(time));
  stats.total_ms = milliseconds_since(start);
  return stats;
}

}  // namespace

bool whole_steps(FrameRows rows, int height, int step) {
  return rows.begin >= 0 && rows.begin % step == 0 && rows.begin < height &&
         rows.end > rows.begin && (rows.end >= height || rows.end % step == 0);
}

FrameStats render_frame_bands(const Scene& scene, const SceneResources& resources,
                              const FrameRequest& request, int band_rows,
                              const std::function<void(const FrameImage&, int)>& consume,
                              FrameRows rows) {
  if (request.backend == Backend::kGl) {
    throw std::invalid_argument("render_frame_bands: the GL backend renders whole frames only");
  }
  if (band_rows <= 0 || band_rows % raster::kTileSize != 0) {
    throw std::invalid_argument("render_frame_bands: band_rows must be a positive multiple of " +
                                std::to_string(raster::kTileSize));
  }
  const int height = scene.viewport.height;
  if (!whole_steps(rows, height, raster::kTileSize)) {
    throw std::invalid_argument("render_frame_bands: rows [" + std::to_string(rows.begin) + ", " +
                                std::to_string(rows.end) + ") of " + std::to_string(height) +
                                " do not start at a multiple of " +
                                std::to_string(raster::kTileSize) +
                                " below the top and end at one or past the top");
  }
  const int end = std::min(rows.end, height);
  return request.backend == Backend::kReferenceDouble
             ? render_bands_with<double>(scene, resources, request, band_rows, rows.begin, end,
                                         consume)
             : render_bands_with<float>(scene, resources, request, band_rows, rows.begin, end,
                                        consume);
}

namespace {

// Rows [first_row, first_row + rows) of each of the image's buffers.
FrameImage image_rows(const FrameImage& image, int first_row, int rows) {
  FrameImage out;
  out.width = image.width;
  out.height = rows;
  const auto cut = [&](const auto& values, auto& into) {
    if (values.empty()) {
      return;
    }
    const std::size_t per_row = values.size() / std::size_t(image.height);
    into.assign(values.begin() + std::ptrdiff_t(per_row * std::size_t(first_row)),
                values.begin() + std::ptrdiff_t(per_row * std::size_t(first_row + rows)));
  };
  cut(image.srgb, out.srgb);
  cut(image.linear, out.linear);
  cut(image.depth, out.depth);
  cut(image.primitive, out.primitive);
  cut(image.normal, out.normal);
  cut(image.world_height, out.world_height);
  cut(image.octaves, out.octaves);
  return out;
}

}  // namespace

Frame render_frame_rows(const Scene& scene, const SceneResources& resources,
                        const FrameRequest& request, int first_row, int rows) {
  const int height = scene.viewport.height;
  if (!whole_steps({first_row, first_row + rows}, height, raster::kTileSize) ||
      first_row + rows > height) {
    throw std::invalid_argument("render_frame_rows: rows [" + std::to_string(first_row) + ", " +
                                std::to_string(first_row + rows) + ") of " +
                                std::to_string(height) + " do not start at a multiple of " +
                                std::to_string(raster::kTileSize) +
                                " and end at one or at the top");
  }
  if (request.backend == Backend::kGl) {
    // GL draws whole frames (gl_backend.h): the rows are kept from one.
    Frame frame = render_frame(scene, resources, request);
    frame.image = image_rows(frame.image, first_row, rows);
    return frame;
  }
  Frame frame;
  const auto keep = [&](const FrameImage& band, int) { frame.image = band; };
  // One band: the rows rounded up to whole tiles (the backend stops at the viewport's top).
  const int band = (rows + raster::kTileSize - 1) / raster::kTileSize * raster::kTileSize;
  frame.stats = request.backend == Backend::kReferenceDouble
                    ? render_bands_with<double>(scene, resources, request, band, first_row,
                                                first_row + rows, keep)
                    : render_bands_with<float>(scene, resources, request, band, first_row,
                                               first_row + rows, keep);
  return frame;
}

Frame render_frame_repeated(const Scene& scene, const SceneResources& resources,
                            const FrameRequest& request, int repeat, double& median_ms) {
  std::vector<double> times;
  Frame frame;
  for (int r = 0; r < std::max(repeat, 1); ++r) {
    const Clock::time_point start = Clock::now();
    frame = render_frame(scene, resources, request);
    times.push_back(milliseconds_since(start));
  }
  std::sort(times.begin(), times.end());
  median_ms = times[times.size() / 2];
  return frame;
}

template <class Real>
TerrainRun<Real> run_terrain_stages(const Scene& scene, const NoiseLattice& lattice, Backend kind,
                                    const HeightSketch* sketch) {
  const Clock::time_point start = Clock::now();
  // The whole grid, seen or not: relief stages writes every vertex.
  if constexpr (std::is_same_v<Real, float>) {
    if (kind == Backend::kGl) {
      GridBuffers<float> grid = gl_terrain_stages(scene, lattice, sketch);
      std::vector<StageTime> times{
          {"GL stages 1-4, read back", milliseconds_since(start), true, {}}};
      return {make_frame_plan(scene, lattice, sketch), std::move(grid), std::move(times)};
    }
  }
  FrameRequest request;
  request.backend = kind;
  request.skips.unseen_vertices = false;
  CpuBackend<Real> backend(scene, lattice, {}, request, sketch);
  std::vector<StageTime> times{{"frame plan", milliseconds_since(start), true, {}}};
  run_table(backend, StageId::kSurface, times);
  return {backend.plan(), backend.take_grid(), std::move(times)};
}

template TerrainRun<float> run_terrain_stages<float>(const Scene&, const NoiseLattice&, Backend,
                                                     const HeightSketch*);
template TerrainRun<double> run_terrain_stages<double>(const Scene&, const NoiseLattice&, Backend,
                                                       const HeightSketch*);

}  // namespace relief
