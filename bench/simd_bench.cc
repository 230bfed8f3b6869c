// The Highway kernels beside the scalar reference, in one run: per kernel, the scalar stage and
// the SIMD stage on every target this CPU runs (forced in turn), single-threaded.
//
// BM_Fbm_*: the fBm in the configuration other noise libraries are measured in (FastNoise2's
// benchmark: 1024 x 1024 points of a plane, 10 octaves of value noise, no warping), counted in
// point-octaves per second (items_per_second). Relief's fBm also forms each octave's lattice
// coordinate camera-relative with the octave's offset, applies the LOD weight, and reads its
// lattice from memory (four gathers per point-octave) where FastNoise2 hashes.
//
// BM_FrameStages/<backend>/<threads>: the default frame (1280 x 1024, 512 x 512 grid) by the
// reference backend and by the simd backend (best target), one after the other in one run; a
// counter per stage of the table holds its mean wall time in ms, and one per part of the fused
// tile stage its CPU time summed over the threads ("cpu: ..."). The ratio per stage is the
// reference's counter over the simd one.
// Run: build/bench/relief_bench_simd --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "simd/fbm.h"

namespace relief {
namespace {

constexpr int kSide = 1024;
constexpr int kOctaves = 10;

struct NoisePlane {
  Scene scene = resolve_scene("default", {"terrain.last_octave=9"});
  NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  FramePlan plan = make_frame_plan(scene, lattice);
  FbmParams<float> params = make_fbm_params<float>(plan.terrain);
  std::vector<float> dx, dz, nu, height;

  NoisePlane() {
    const std::size_t points = std::size_t(kSide) * kSide;
    dx.resize(points);
    dz.resize(points);
    nu.assign(points, float(kOctaves));
    height.resize(points);
    // A plane of 1024 x 1024 points, 0.7 world units apart (about 4 points per finest cell).
    for (int j = 0; j < kSide; ++j) {
      for (int i = 0; i < kSide; ++i) {
        dx[std::size_t(j) * kSide + i] = float(i) * 0.7f - 358.0f;
        dz[std::size_t(j) * kSide + i] = float(j) * 0.7f - 358.0f;
      }
    }
    std::fill(std::begin(params.exact_coordinates), std::end(params.exact_coordinates), 0);
  }
};

NoisePlane& plane() {
  static NoisePlane p;
  return p;
}

void count_point_octaves(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * std::int64_t(kSide) * kSide * kOctaves);
}

void BM_Fbm_Scalar(benchmark::State& state) {
  NoisePlane& p = plane();
  for (auto _ : state) {
    evaluate_fbm<float>(p.params, p.lattice, IndexRange{0, p.height.size()}, p.dx, p.dz, p.nu, {},
                        p.height);
    benchmark::ClobberMemory();
  }
  count_point_octaves(state);
}

void BM_Fbm_Simd(benchmark::State& state, std::string target) {
  force_simd_target(target);
  NoisePlane& p = plane();
  for (auto _ : state) {
    simd::evaluate_fbm(p.params, p.lattice, IndexRange{0, p.height.size()}, p.dx, p.dz, p.nu, {},
                       p.height);
    benchmark::ClobberMemory();
  }
  count_point_octaves(state);
  force_simd_target("best");
}

struct DefaultScene {
  Scene scene = resolve_scene("default", {});
  SceneResources resources = load_scene_resources(scene);
};

DefaultScene& default_scene() {
  static DefaultScene d;
  return d;
}

void BM_FrameStages(benchmark::State& state, Backend backend) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(state.range(0)));
  FrameRequest request;
  request.backend = backend;
  std::map<std::string, double> sums;
  for (auto _ : state) {
    const Frame frame = render_frame(default_scene().scene, default_scene().resources, request);
    for (const StageTime& stage : frame.stats.stages) {
      sums[stage.name] += stage.ms;
    }
    for (const StageTime& part : frame.stats.tile_parts) {
      sums["cpu: " + part.name] += part.ms;
    }
    sums["frame"] += frame.stats.total_ms;
  }
  for (const auto& [name, ms] : sums) {
    state.counters[name] = benchmark::Counter(ms / double(state.iterations()));
  }
}

void register_benchmarks() {
  for (const Backend backend : {Backend::kReference, Backend::kSimd}) {
    benchmark::RegisterBenchmark(("BM_FrameStages/" + std::string(backend_name(backend))).c_str(),
                                 BM_FrameStages, backend)
        ->Arg(1)
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark("BM_Fbm_Scalar", BM_Fbm_Scalar)->Unit(benchmark::kMillisecond);
  for (const SimdTargetInfo& t : build_info().simd_targets) {
    if (t.supported) {
      benchmark::RegisterBenchmark(("BM_Fbm_Simd/" + t.name).c_str(), BM_Fbm_Simd, t.name)
          ->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace
}  // namespace relief

int main(int argc, char** argv) {
  relief::register_benchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
