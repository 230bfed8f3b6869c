// Stage times of the default scene (1280 x 1024 viewport, 512 x 512 grid), scalar reference,
// one thread and all threads. Run: build/bench/relief_bench_stages --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true. Items per second = grid vertices per second.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "pipeline/frame.h"

namespace relief {
namespace {

struct DefaultFrame {
  Scene scene = resolve_scene("default", {});
  NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  FramePlan plan = make_frame_plan(scene, lattice);
  TerrainParams<float> params = make_terrain_params<float>(plan);
  GridBuffers<float> buffers{plan.layout};
  DefaultFrame() {
    run_terrain_stages(plan, buffers);
    choose_coordinate_forms(plan.terrain, reach(buffers), params.fbm);
  }

  static OctaveReach reach(const GridBuffers<float>& b) {
    return octave_reach<float>(IndexRange{0, b.layout.size()}, b.dx, b.dz, b.nu, b.valid);
  }
};

DefaultFrame& frame() {
  static DefaultFrame f;
  return f;
}

RowRange all_rows() {
  return RowRange{0, frame().plan.layout.height};
}

void set_vertices(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * frame().plan.layout.width *
                          frame().plan.layout.height);
}

// Baseline: the cost of touching every output once (the floor for any stage).
void BM_Baseline_ClearHeight(benchmark::State& state) {
  auto& b = frame().buffers;
  for (auto _ : state) {
    std::fill(b.height.begin(), b.height.end(), 0.0f);
    benchmark::DoNotOptimize(b.height.data());
  }
  set_vertices(state);
}

void BM_Stage2_ProjectedDomain(benchmark::State& state) {
  for (auto _ : state) {
    project_domain<float>(frame().params.domain, frame().params.domain_rows, all_rows(),
                          frame().buffers.domain());
    benchmark::ClobberMemory();
  }
  set_vertices(state);
}

void BM_Stage3_Fractal(benchmark::State& state) {
  for (auto _ : state) {
    evaluate_fbm_rows<float>(frame().params.fbm, frame().lattice, all_rows(), frame().buffers);
    benchmark::ClobberMemory();
  }
  set_vertices(state);
}

void BM_Stage3_FractalWarped(benchmark::State& state) {
  Scene scene = resolve_scene("lava", {});
  const FramePlan plan = make_frame_plan(scene, frame().lattice);
  TerrainParams<float> params = make_terrain_params<float>(plan);
  GridBuffers<float> b(plan.layout);
  project_domain<float>(params.domain, params.domain_rows, all_rows(), b.domain());
  choose_coordinate_forms(plan.terrain, DefaultFrame::reach(b), params.fbm);
  for (auto _ : state) {
    evaluate_fbm_rows<float>(params.fbm, frame().lattice, all_rows(), b);
    benchmark::ClobberMemory();
  }
  set_vertices(state);
}

void BM_Stage4_Surface(benchmark::State& state) {
  for (auto _ : state) {
    surface_pass<float>(frame().params.surface, all_rows(), surface_inputs(frame().buffers),
                        frame().buffers.surface());
    benchmark::ClobberMemory();
  }
  set_vertices(state);
}

// Stages 1-4 through the stage table's runner (pipeline/frame.h), plan included; the argument
// is the thread count.
void BM_Stages1to4_Threads(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(run_terrain_stages<float>(frame().scene, frame().lattice));
  }
  set_vertices(state);
}

BENCHMARK(BM_Baseline_ClearHeight)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stage2_ProjectedDomain)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stage3_Fractal)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stage3_FractalWarped)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stage4_Surface)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stages1to4_Threads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace relief

BENCHMARK_MAIN();
