// The GL compute stages 1-4 (gpu/gl_terrain.h) against the CPU reference in float, on whole
// frames: the figures of docs/gl-backend.md. For each scene, runs stages 2-4 on the CPU
// (core/terrain_stages.h) and through GlTerrain on the current GL (Mesa's llvmpipe here, a
// GPU's driver where there is one) with the same parameters, and prints two rows: "chain",
// the GL's buffers against the CPU's end to end, and "staged", each GL stage against the CPU
// stage run on the GL's own inputs (gpu::staged_reference). Columns: the vertices valid in
// both, valid-mask differences, the share of vertices whose stage 2, 3 and 4 outputs are
// bit-identical, then the largest relative domain error, sigma error (relative to the
// distance), octave-count error, height error (max and RMS, relative to the height scale A),
// normal angle (radians), slope error (relative to 1 + slope) and water-depth error. A third
// row, "f-d", gives the CPU's float stage 3 against double on the same inputs, and a fourth the
// GL's time for stages 2-4.
// Run: build/bench/relief_gl_terrain_report [grid side, default 256]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "gpu/gl_terrain.h"
#include "gpu/gl_terrain_differences.h"
#include "gpu/headless_gl.h"

namespace relief {
namespace {

struct Case {
  const char* name;
  const char* preset;
  std::vector<std::string> overrides;
};

void print(const char* name, const char* kind, const gpu::TerrainDifferences& d, double a) {
  const auto share = [&](std::size_t n) { return 100.0 * double(n) / double(d.vertices); };
  std::printf(
      "%-13s %-6s %6zu %3zu %6.2f%% %6.2f%% %6.2f%% %8.1e %8.1e %8.1e %8.1e %8.1e %8.1e %8.1e "
      "%8.1e\n",
      name, kind, d.vertices, d.valid_mismatches, share(d.identical_domain),
      share(d.identical_height), share(d.identical_surface), d.domain_max_rel, d.sigma_max_rel,
      d.nu_max_abs, d.height_max_abs / a, d.height_rms_abs / a, d.normal_max_angle, d.slope_max_rel,
      d.water_max_abs / a);
}

void report(const Case& c, int grid) {
  std::vector<std::string> all = {"grid.width=" + std::to_string(grid),
                                  "grid.height=" + std::to_string(grid)};
  all.insert(all.end(), c.overrides.begin(), c.overrides.end());
  const Scene scene = resolve_scene(c.preset, all);
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> cpu(plan.layout), gl(plan.layout);
  run_terrain_stages(plan, cpu);
  TerrainParams<float> cpu_params = make_terrain_params<float>(plan);
  choose_coordinate_forms(
      plan.terrain,
      octave_reach<float>(IndexRange{0, cpu.layout.size()}, cpu.dx, cpu.dz, cpu.nu, cpu.valid),
      cpu_params.fbm);

  gpu::GlTerrain terrain(plan.layout, lattice);
  terrain.run(make_terrain_params<float>(plan));
  terrain.read_all(gl);
  const double a = plan.terrain.amplitude;
  print(c.name, "chain", gpu::terrain_differences(cpu, gl), a);
  const GridBuffers<float> staged = gpu::staged_reference(plan, cpu, gl);
  print("", "staged", gpu::terrain_differences(staged, gl), a);
  // How far the CPU's float stage 3 is from the same function in double, on the same inputs:
  // the yardstick of the warp's bound (docs/gl-backend.md).
  const std::size_t size = plan.layout.size();
  AlignedVector<double> dx(size), dz(size), nu(size), exact(size);
  for (std::size_t k = 0; k < size; ++k) {
    dx[k] = gl.dx[k];
    dz[k] = gl.dz[k];
    nu[k] = gl.nu[k];
  }
  FbmParams<double> fbm = make_fbm_params<double>(plan.terrain);
  choose_coordinate_forms(plan.terrain, octave_reach<double>({0, size}, dx, dz, nu, gl.valid), fbm);
  evaluate_fbm<double>(fbm, lattice, {0, size}, dx, dz, nu, gl.valid, exact);
  double worst = 0, sum_sq = 0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < size; ++k) {
    if (gl.valid[k]) {
      const double e = std::abs(double(staged.height[k]) - exact[k]);
      worst = std::max(worst, e);
      sum_sq += e * e;
      ++count;
    }
  }
  std::printf("%-13s %-6s float stage 3 - double on the same inputs: h max/A %.1e, h rms/A %.1e\n",
              "", "f-d", worst / a, std::sqrt(sum_sq / double(count)) / a);
  const FbmParams<float> gl_fbm = terrain.fbm_params();
  for (int n = 0; n < cpu_params.fbm.count; ++n) {
    if (gl_fbm.exact_coordinates[n] != cpu_params.fbm.exact_coordinates[n]) {
      std::printf("  octave %d: the GL chose the %s form, the CPU the other\n", n,
                  gl_fbm.exact_coordinates[n] ? "exact" : "direct");
    }
  }
  // The time of the three stages, compiled programs and buffers ready (the median of 5).
  std::vector<double> ms;
  for (int run = 0; run < 5; ++run) {
    const auto start = std::chrono::steady_clock::now();
    terrain.run(make_terrain_params<float>(plan));
    glFinish();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::sort(ms.begin(), ms.end());
  std::printf("%-13s %-6s %.2f ms (stages 2-4 on the GL)\n", "", "time", ms[2]);
}

}  // namespace
}  // namespace relief

int main(int argc, char** argv) {
  const int grid = argc > 1 ? std::atoi(argv[1]) : 256;
  std::string error;
  const auto gl = relief::gpu::HeadlessGl::open(error);
  if (!gl) {
    std::fprintf(stderr, "relief_gl_terrain_report: %s\n", error.c_str());
    return 2;
  }
  std::printf("renderer: %s, grid %d x %d\n", gl->renderer().c_str(), grid, grid);
  std::printf("%-13s %-6s %6s %3s %7s %7s %7s %8s %8s %8s %8s %8s %8s %8s %8s\n", "scene", "",
              "verts", "val", "st2 id", "st3 id", "st4 id", "d rel", "sig rel", "nu abs", "h max/A",
              "h rms/A", "n rad", "slope", "water/A");
  const std::vector<relief::Case> cases = {
      {"default", "default", {}},
      {"alpine", "alpine", {}},
      {"dunes", "dunes", {}},
      {"lake", "lake", {}},
      {"lava", "lava", {}},
      {"plain", "plain", {}},
      {"far 1e9", "default", {"terrain.r=2.17", "camera.position=[1e9,700,2.5e8]"}},
      {"far 1e12", "default", {"camera.position=[1e12,700,-1e12]"}},
      {"exact H=0.05", "default", {"terrain.H=0.05", "terrain.last_octave=23"}},
      {"warp r0 t0", "lava", {"terrain.warp.r0=[3,4]", "terrain.warp.t0=[0.5,-0.25]"}},
      {"linear -35", "alpine", {"terrain.interpolant=\"linear\"", "camera.pitch_deg=-35"}},
      {"cubic +12", "dunes", {"terrain.interpolant=\"cubic\"", "camera.pitch_deg=12"}},
  };
  try {
    for (const relief::Case& c : cases) {
      relief::report(c, grid);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relief_gl_terrain_report: %s\n", e.what());
    return 2;
  }
  return 0;
}
