// Whole frames of the default scene (1280 x 1024 viewport, 512 x 512 grid, the paper's
// settings) side by side in one run: the tile-fused frame of the library in float (scalar and
// simd backends, the same bytes) and in double,
// and the same stages composed over whole-frame buffers (tests/oracles/whole_frame.h, the layout
// before the fusion). The argument is the thread count. Run:
//   build/bench/relief_bench_frame --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

struct DefaultScene {
  Scene scene = resolve_scene("default", {});
  SceneResources resources = load_scene_resources(scene);
};

DefaultScene& defaults() {
  static DefaultScene d;
  return d;
}

void BM_Frame_Fused(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_frame(defaults().scene, defaults().resources, {}));
  }
}

void BM_Frame_FusedSimd(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  FrameRequest request;
  request.backend = Backend::kSimd;
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_frame(defaults().scene, defaults().resources, request));
  }
}

void BM_Frame_FusedDouble(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  FrameRequest request;
  request.backend = Backend::kReferenceDouble;
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_frame(defaults().scene, defaults().resources, request));
  }
}

void BM_Frame_WholeFrameBuffers(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_whole_frame(defaults().scene, defaults().resources));
  }
}

BENCHMARK(BM_Frame_Fused)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_FusedSimd)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_FusedDouble)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_WholeFrameBuffers)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace relief

BENCHMARK_MAIN();
