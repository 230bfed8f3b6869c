// The rasteriser on the default terrain frame (1280 x 1024 viewport, 512 x 512 grid) and on
// screen-filling sweeps of equal-sized triangles, with a clear-only baseline.
// Run: build/bench/relief_bench_raster --benchmark_repetitions=5
//        --benchmark_report_aggregates_only=true
// Counters: triangles = submitted per second; set_up = pieces that survived culling and
// clipping per second; pixels = covered pixels per second (sweeps).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "raster/rasterize.h"
#include "raster/resolve.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

struct DefaultTerrain {
  Scene scene = resolve_scene("default", {});
  NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  TerrainFrame frame = rasterize_terrain(scene, lattice);
};

DefaultTerrain& terrain() {
  static DefaultTerrain t;
  return t;
}

void BM_Baseline_ClearVisibilityBuffer(benchmark::State& state) {
  const raster::RasterState& s = terrain().frame.state;
  for (auto _ : state) {
    raster::VisibilityBuffer b = raster::make_visibility_buffer(s);
    benchmark::DoNotOptimize(b.primitive.data());
  }
}

// Stage 6 on the default frame; the argument is the thread count.
void BM_Raster_DefaultTerrain(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  const TerrainFrame& f = terrain().frame;
  raster::VisibilityBuffer out;
  raster::RasterStats stats;
  for (auto _ : state) {
    stats = raster::rasterize(f.state, f.clip(), f.triangles(), out);
    benchmark::DoNotOptimize(out.primitive.data());
  }
  state.counters["triangles"] =
      benchmark::Counter(double(stats.triangles) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["set_up"] =
      benchmark::Counter(double(stats.setup) * state.iterations(), benchmark::Counter::kIsRate);
}

// Stage 7 as the renderer runs it (eight attribute streams, derivatives of three) on the
// default frame.
void BM_Resolve_DefaultTerrain(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  const TerrainFrame& f = terrain().frame;
  const std::span<const float> streams[8] = {f.grid.dx,    f.grid.dz,         f.grid.height,
                                             f.grid.nx,    f.grid.ny,         f.grid.nz,
                                             f.grid.slope, f.grid.water_depth};
  raster::ResolvedFrame out;
  for (auto _ : state) {
    raster::resolve(f.visibility, raster::VertexPositions::from_clip(f.clip(), f.state.viewport),
                    f.triangles(), std::span<const std::span<const float>>(streams), 3, out);
    benchmark::DoNotOptimize(out.b0.data());
  }
}

// Right triangles of `side` px legs tiling 1280 x 1024 (two per square), slightly offset so
// that edges do not fall on pixel centres; one thread.
void BM_Raster_TriangleSizeSweep(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const float side = static_cast<float>(state.range(0));
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> indices;
  auto vertex = [&](float vx, float vy) {
    indices.push_back(static_cast<std::uint32_t>(x.size()));
    x.push_back(vx);
    y.push_back(vy);
    z.push_back(0.5f);
  };
  for (float sy = 0.3f; sy < 1024; sy += side) {
    for (float sx = 0.3f; sx < 1280; sx += side) {
      vertex(sx, sy), vertex(sx + side, sy), vertex(sx + side, sy + side);
      vertex(sx, sy), vertex(sx + side, sy + side), vertex(sx, sy + side);
    }
  }
  raster::RasterState s;
  s.width = 1280;
  s.height = 1024;
  s.viewport = {0, 0, 1280, 1024};
  s.depth_test = raster::DepthTest::kAlways;
  raster::VisibilityBuffer out;
  for (auto _ : state) {
    raster::rasterize(s, raster::WindowVertices{x, y, z}, raster::IndexedTriangles{indices}, out);
    benchmark::DoNotOptimize(out.primitive.data());
  }
  const double triangles = double(indices.size() / 3);
  state.counters["triangles"] =
      benchmark::Counter(triangles * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["pixels"] =
      benchmark::Counter(1280.0 * 1024 * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Baseline_ClearVisibilityBuffer)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Raster_DefaultTerrain)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Resolve_DefaultTerrain)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Raster_TriangleSizeSweep)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Arg(64)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace relief

BENCHMARK_MAIN();
