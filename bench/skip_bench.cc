// Frames of scenes that need less than the default one (docs/stages.md, "Skipped work"), each
// with the frame's skips on and with every skip off, side by side in one run: the time falls with
// the work, and the counters say which work. Frames of the default viewport and grid (1280 x
// 1024, 512 x 512), on all threads. Run:
//   build/bench/relief_bench_skip --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"

namespace relief {
namespace {

struct LightScene {
  const char* name;
  std::vector<std::string> overrides;
};

// The default scene, then scenes that need less of it.
const LightScene kScenes[] = {
    {"default", {}},
    // The horizon across the middle of the image: the top half is sky.
    {"half_sky", {"camera.pitch_deg=0"}},
    // No water level: no water depth, no water pass, no open water.
    {"no_water", {"terrain.water_level=null"}},
    // From 20 km up the finest octaves are below a pixel everywhere.
    {"distant_low_detail", {"camera.position=[0, 20000, 0]", "camera.pitch_deg=-30"}},
    // Straight down: no horizon, no sky, every vertex near.
    {"straight_down", {"camera.pitch_deg=-90"}},
    // Looking up: the terrain fills a strip at the bottom of the image (12% of the pixels).
    {"mostly_sky", {"camera.pitch_deg=25"}},
};

struct Prepared {
  Scene scene;
  SceneResources resources;
};

const Prepared& prepared(int index) {
  static std::vector<Prepared> scenes = [] {
    std::vector<Prepared> out;
    for (const LightScene& s : kScenes) {
      Scene scene = resolve_scene("default", s.overrides);
      SceneResources resources = load_scene_resources(scene);
      out.push_back({std::move(scene), std::move(resources)});
    }
    return out;
  }();
  return scenes[static_cast<std::size_t>(index)];
}

std::uint64_t counter(const Frame& frame, const char* name) {
  for (const StageTime& stage : frame.stats.stages) {
    for (const WorkCounter& c : stage.counters) {
      if (c.name == name) {
        return c.value;
      }
    }
  }
  return 0;
}

// range(0): the scene; range(1): 1 with the skips, 0 with none.
void BM_Frame(benchmark::State& state) {
  const Prepared& p = prepared(static_cast<int>(state.range(0)));
  FrameRequest request;
  if (state.range(1) == 0) {
    request.skips = {false, false, false, false, false, false, false, false, false};
  }
  Frame frame;
  for (auto _ : state) {
    frame = render_frame(p.scene, p.resources, request);
    benchmark::DoNotOptimize(frame.image.srgb.data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)].name) +
                 (state.range(1) ? " skips on" : " skips off"));
  for (const char* name : {"vertices evaluated", "point-octaves summed", "triangles submitted",
                           "triangles set up", "tiles rasterised", "pixels shaded as terrain",
                           "texture fetches", "water pixels", "fogged pixels"}) {
    state.counters[name] = benchmark::Counter(double(counter(frame, name)));
  }
}

void scenes(benchmark::internal::Benchmark* b) {
  for (int s = 0; s < int(std::size(kScenes)); ++s) {
    b->Args({s, 1});
    b->Args({s, 0});
  }
}

BENCHMARK(BM_Frame)->Apply(scenes)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace relief

BENCHMARK_MAIN();
