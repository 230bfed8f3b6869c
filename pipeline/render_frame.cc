#include "pipeline/render_frame.h"

#include <chrono>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/input_file.h"
#include "core/shade.h"
#include "core/shading_plan.h"
#include "core/srgb.h"
#include "core/vertex_transform.h"
#include "pipeline/memory_budget.h"
#include "raster/resolve.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Image rows per task in stages 8 and 9: a 1280-pixel row shades in ~0.1 ms.
constexpr int kImageRowsPerTask = 8;

}  // namespace

raster::RasterState frame_raster_state(const Scene& scene) {
  raster::RasterState state;
  state.width = scene.viewport.width;
  state.height = scene.viewport.height;
  state.viewport = {0.0, 0.0, double(scene.viewport.width), double(scene.viewport.height)};
  state.cull = raster::CullMode::kBack;
  state.depth_test = raster::DepthTest::kGreater;
  state.depth_clear = 0.0f;
  return state;
}

TerrainFrame rasterize_terrain(const Scene& scene, const NoiseLattice& lattice,
                               FrameTimings& timings, const raster::RasterLimits& limits) {
  FramePlan frame_plan = make_frame_plan(scene, lattice);
  const GridLayout layout = frame_plan.layout;
  TerrainFrame frame{std::move(frame_plan),
                     GridBuffers<float>(layout),
                     {},
                     {},
                     {},
                     {},
                     frame_raster_state(scene),
                     {}};
  const FramePlan& plan = frame.plan;
  GridBuffers<float>& grid = frame.grid;
  timings.terrain = run_terrain_stages_parallel(plan, grid);

  // Stage 5.
  auto start = Clock::now();
  const std::size_t vertex_count = plan.layout.size();
  frame.clip_x.resize(vertex_count);
  frame.clip_y.resize(vertex_count);
  frame.clip_z.resize(vertex_count);
  frame.clip_w.resize(vertex_count);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, vertex_count, 16384),
      [&](const tbb::blocked_range<std::size_t>& r) {
        transform_vertices<float>(
            plan.clip, IndexRange{r.begin(), r.end()}, grid.dx, grid.dz, grid.height,
            ClipSpans<float>{frame.clip_x, frame.clip_y, frame.clip_z, frame.clip_w});
      },
      tbb::simple_partitioner());
  timings.transform_ms = milliseconds_since(start);

  // Stage 6.
  start = Clock::now();
  timings.raster =
      raster::rasterize(frame.state, frame.clip(), frame.triangles(), frame.visibility, limits);
  if (timings.raster.bins_refused) {
    throw MemoryLimitError("the rasteriser's bins for this frame need " +
                           format_bytes(timings.raster.bin_bytes) + ", more than the " +
                           format_bytes(limits.max_bin_bytes) +
                           " left of the memory budget; lower viewport.width/height");
  }
  timings.raster_ms = milliseconds_since(start);
  return frame;
}

raster::ResolvedFrame resolve_for_shading(const TerrainFrame& frame) {
  const GridBuffers<float>& g = frame.grid;
  const std::span<const float> streams[] = {g.dx, g.dz, g.height, g.nx,
                                            g.ny, g.nz, g.slope,  g.water_depth};
  raster::ResolvedFrame resolved;
  raster::resolve(frame.visibility,
                  raster::VertexPositions::from_clip(frame.clip(), frame.state.viewport),
                  frame.triangles(), std::span<const std::span<const float>>(streams), 3, resolved);
  return resolved;
}

ShadingInputs shading_inputs(const TerrainFrame& frame, const raster::ResolvedFrame& r) {
  return ShadingInputs{frame.visibility.primitive,
                       r.value[0],
                       r.value[1],
                       r.value[2],
                       r.ddx[0],
                       r.ddy[0],
                       r.ddx[1],
                       r.ddy[1],
                       r.ddx[2],
                       r.ddy[2],
                       r.value[3],
                       r.value[4],
                       r.value[5],
                       r.value[6],
                       r.value[7]};
}

RenderedImage render_frame(const Scene& scene, const SceneResources& resources,
                           FrameTimings& timings, const raster::RasterLimits& limits) {
  const TerrainFrame frame = rasterize_terrain(scene, resources.lattice, timings, limits);

  // Stage 7.
  auto start = Clock::now();
  const raster::ResolvedFrame resolved = resolve_for_shading(frame);
  timings.resolve_ms = milliseconds_since(start);

  // Stage 8.
  start = Clock::now();
  const ShadingPlan plan =
      make_shading_plan(scene, frame.plan, resources.textures, resources.lattice);
  const ShadingInputs inputs = shading_inputs(frame, resolved);
  RenderedImage image;
  image.width = frame.state.width;
  image.height = frame.state.height;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  image.linear.resize(3 * pixels);
  parallel_rows(image.height, kImageRowsPerTask,
                [&](RowRange rows) { shade_pixels<float>(plan, inputs, rows, image.linear); });
  timings.shade_ms = milliseconds_since(start);

  // Stage 9: sRGB encoding.
  start = Clock::now();
  image.rgb.resize(3 * pixels);
  parallel_rows(image.height, kImageRowsPerTask, [&](RowRange rows) {
    const std::size_t begin = 3 * std::size_t(rows.begin) * image.width;
    const std::size_t end = 3 * std::size_t(rows.end) * image.width;
    for (std::size_t k = begin; k < end; ++k) {
      image.rgb[k] = srgb_byte(image.linear[k]);
    }
  });
  timings.encode_ms = milliseconds_since(start);
  return image;
}

}  // namespace relief
