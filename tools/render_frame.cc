#include "tools/render_frame.h"

#include <chrono>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/frame_plan.h"
#include "core/srgb.h"
#include "core/vertex_transform.h"
#include "raster/resolve.h"
#include "raster/topology.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Rgb {
  double r, g, b;
};

// Diagnostic look: a low sun from the left-front of the default camera, so relief reads well.
const glm::dvec3 kSunDirection = glm::normalize(glm::dvec3(-0.6, 0.5, -0.3));
constexpr Rgb kGround{0.42, 0.40, 0.33};
constexpr Rgb kSkyZenith{0.22, 0.40, 0.75};
constexpr Rgb kSkyHorizon{0.70, 0.78, 0.88};
constexpr double kAmbient = 0.12;

Rgb mix(const Rgb& a, const Rgb& b, double t) {
  return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

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
                               FrameTimings& timings) {
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertex_count, 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      transform_vertices<float>(
                          plan.clip, IndexRange{r.begin(), r.end()}, grid.dx, grid.dz, grid.height,
                          ClipSpans<float>{frame.clip_x, frame.clip_y, frame.clip_z, frame.clip_w});
                    });
  timings.transform_ms = milliseconds_since(start);

  // Stage 6.
  start = Clock::now();
  timings.raster =
      raster::rasterize(frame.state, frame.clip(), frame.triangles(), frame.visibility);
  timings.raster_ms = milliseconds_since(start);
  return frame;
}

RenderedImage render_diagnostic_frame(const Scene& scene, const NoiseLattice& lattice,
                                      FrameTimings& timings) {
  const TerrainFrame frame = rasterize_terrain(scene, lattice, timings);
  const FramePlan& plan = frame.plan;
  const GridBuffers<float>& grid = frame.grid;
  const raster::RasterState& state = frame.state;
  const raster::VisibilityBuffer& visibility = frame.visibility;
  const raster::ClipVertices clip = frame.clip();
  const raster::GridTriangles triangles = frame.triangles();

  // Stage 7: the normal, perspective-correct.
  auto start = Clock::now();
  const std::span<const float> streams[3] = {grid.nx, grid.ny, grid.nz};
  raster::ResolvedFrame resolved;
  raster::resolve(visibility, raster::VertexPositions::from_clip(clip, state.viewport), triangles,
                  std::span<const std::span<const float>>(streams), resolved);
  timings.resolve_ms = milliseconds_since(start);

  // Diagnostic shading.
  start = Clock::now();
  RenderedImage image;
  image.width = state.width;
  image.height = state.height;
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  const CameraFrame& camera = plan.camera;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, image.height), [&](const tbb::blocked_range<int>& r) {
        for (int py = r.begin(); py < r.end(); ++py) {
          for (int px = 0; px < image.width; ++px) {
            const std::size_t k = visibility.index(px, py);
            Rgb color;
            if (visibility.primitive[k] != raster::kNoPrimitive) {
              glm::dvec3 n(resolved.value[0][k], resolved.value[1][k], resolved.value[2][k]);
              const double length = glm::length(n);
              n = length > 0.0 ? n / length : glm::dvec3(0, 1, 0);  // domain: length > 0
              const double light =
                  kAmbient + (1.0 - kAmbient) * std::max(0.0, glm::dot(n, kSunDirection));
              color = {kGround.r * light, kGround.g * light, kGround.b * light};
            } else {
              const double ndc_x = 2.0 * (px + 0.5) / image.width - 1.0;
              const double ndc_y = 2.0 * (py + 0.5) / image.height - 1.0;
              const glm::dvec3 ray =
                  glm::normalize(camera.forward + ndc_x * camera.tan_half_fov_x * camera.right +
                                 ndc_y * camera.tan_half_fov_y * camera.up);
              color = mix(kSkyHorizon, kSkyZenith, std::sqrt(std::max(0.0, ray.y)));
            }
            std::uint8_t* out = &image.rgb[k * 3];
            out[0] = srgb_byte(color.r);
            out[1] = srgb_byte(color.g);
            out[2] = srgb_byte(color.b);
          }
        }
      });
  timings.shade_ms = milliseconds_since(start);
  return image;
}

}  // namespace relief
