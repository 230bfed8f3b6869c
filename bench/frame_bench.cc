// Whole frames of the default scene (1280 x 1024 viewport, 512 x 512 grid, the paper's
// settings) side by side in one run: the tile-fused frame of the library in float (scalar and
// simd backends, the same bytes) and in double,
// and the same stages composed over whole-frame buffers (tests/oracles/whole_frame.h, the layout
// before the fusion). The argument is the thread count. BM_Process_Render is what a CI job that
// renders one image per process pays: `relief render` of the default scene end to end (start-up,
// scene set-up, the first frame, PNG encoding and writing), a fresh process each time. Run:
//   build/bench/relief_bench_frame --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <tbb/global_control.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

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

// `relief render -o DIR/bench.png --threads N` in a fresh process, its output discarded.
void BM_Process_Render(benchmark::State& state) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("relief-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "bench.png").string();
  const std::string threads = std::to_string(state.range(0));
  const char* argv[] = {RELIEF_BINARY, "render",        "-o",   out.c_str(),
                        "--threads",   threads.c_str(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  for (auto _ : state) {
    pid_t pid = 0;
    int status = 0;
    if (posix_spawn(&pid, RELIEF_BINARY, &actions, nullptr, const_cast<char**>(argv), environ) !=
            0 ||
        waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      state.SkipWithError("relief render did not run or failed");
      break;
    }
  }
  posix_spawn_file_actions_destroy(&actions);
  std::filesystem::remove_all(dir);
}

BENCHMARK(BM_Process_Render)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_Fused)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_FusedSimd)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_FusedDouble)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame_WholeFrameBuffers)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace relief

BENCHMARK_MAIN();
