#include "pipeline/frame.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "pipeline/gl_backend.h"
#include "pipeline/reference_backend.h"
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

template <class Real>
Frame render_with(const Scene& scene, const SceneResources& resources,
                  const FrameRequest& request) {
  const Clock::time_point start = Clock::now();
  std::unique_ptr<FrameBackend> backend;
  if (request.backend == Backend::kGl) {
    backend = make_gl_backend(scene, resources, request);
  } else {
    backend = std::make_unique<ReferenceBackend<Real>>(scene, resources.lattice, resources.textures,
                                                       request);
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
TerrainRun<Real> run_terrain_stages(const Scene& scene, const NoiseLattice& lattice, Backend kind) {
  const Clock::time_point start = Clock::now();
  // The whole grid, seen or not: relief stages writes every vertex.
  if constexpr (std::is_same_v<Real, float>) {
    if (kind == Backend::kGl) {
      GridBuffers<float> grid = gl_terrain_stages(scene, lattice);
      std::vector<StageTime> times{
          {"GL stages 1-4, read back", milliseconds_since(start), true, {}}};
      return {make_frame_plan(scene, lattice), std::move(grid), std::move(times)};
    }
  }
  FrameRequest request;
  request.backend = kind;
  request.skips.unseen_vertices = false;
  ReferenceBackend<Real> backend(scene, lattice, {}, request);
  std::vector<StageTime> times{{"frame plan", milliseconds_since(start), true, {}}};
  run_table(backend, StageId::kSurface, times);
  return {backend.plan(), backend.take_grid(), std::move(times)};
}

template TerrainRun<float> run_terrain_stages<float>(const Scene&, const NoiseLattice&, Backend);
template TerrainRun<double> run_terrain_stages<double>(const Scene&, const NoiseLattice&, Backend);

}  // namespace relief
