// Float pipeline versus double pipeline on whole frames: the accuracy figures of stages 2-4.
// For each preset and camera distance from the origin, runs stages 2-4 in float and in double
// at the same camera and prints the height error (median, 99th percentile, max over vertices
// valid in both), the largest normal-component error, and the octave-count error. The last
// rows lift terrain and camera together (base height 1e7): heights are camera-relative, so the
// figures must not change.
// Run: build/bench/relief_precision_report [grid side, default 512]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"

namespace relief {
namespace {

void report(const std::string& preset, double distance, double lift, int grid) {
  const std::string side = std::to_string(grid);
  Scene scene = resolve_scene(preset, {"grid.width=" + side, "grid.height=" + side});
  scene.camera.position[0] += 0.6 * distance;
  scene.camera.position[2] -= 0.8 * distance;
  scene.camera.position[1] += lift;
  scene.terrain.base_height += lift;
  if (scene.terrain.water_level) {
    *scene.terrain.water_level += lift;
  }
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> f(plan.layout);
  GridBuffers<double> d(plan.layout);
  run_terrain_stages(plan, f);
  run_terrain_stages(plan, d);
  std::vector<double> height;
  double normal = 0, nu = 0;
  for (std::size_t k = 0; k < f.layout.size(); ++k) {
    if (f.valid[k] && d.valid[k]) {
      height.push_back(std::abs(f.height[k] - d.height[k]));
      normal = std::max({normal, std::abs(f.nx[k] - d.nx[k]), std::abs(f.ny[k] - d.ny[k]),
                         std::abs(f.nz[k] - d.nz[k])});
      nu = std::max(nu, std::abs(f.nu[k] - d.nu[k]));
    }
  }
  std::sort(height.begin(), height.end());
  const auto at = [&](double p) { return height[std::size_t(p * (height.size() - 1))]; };
  std::printf("%-8s %8.0e %8.0e %9zu %11.2e %11.2e %11.2e %11.2e %11.2e\n", preset.c_str(),
              distance, scene.terrain.base_height, height.size(), at(0.5), at(0.99), height.back(),
              normal, nu);
}

}  // namespace
}  // namespace relief

int main(int argc, char** argv) {
  const int grid = argc > 1 ? std::atoi(argv[1]) : 512;
  std::printf("float versus double, %dx%d grid; height errors in world units\n", grid, grid);
  std::printf("%-8s %8s %8s %9s %11s %11s %11s %11s %11s\n", "preset", "distance", "base h",
              "vertices", "h median", "h p99", "h max", "normal max", "nu max");
  for (const char* preset : {"default", "lava"}) {
    for (double distance : {0.0, 1e3, 1e6, 1e9}) {
      relief::report(preset, distance, 0.0, grid);
    }
  }
  for (const char* preset : {"default", "lava"}) {
    relief::report(preset, 0.0, 1e7 - 100.0, grid);
  }
  return 0;
}
