// The GL backend against the CPU backend on whole frames, at the scene's own settings: the
// figures relief crosscheck prints (eval/frame_comparison.h) and the frame times, without
// OpenImageIO, so that it runs on a GPU machine that has only the GL driver. For each preset
// (or the scenes named), renders the frame with every output by the simd backend (2 threads
// and all threads) and by the GL backend, `repeat` times each, and prints the median times,
// their ratio, and the differences: stages 1-4 at the vertices, the triangle per pixel, the
// per-pixel outputs and the sRGB image.
// Run: build/bench/relief_gl_frame_report [repeat, default 5] [preset ...]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "core/scene/scene_json.h"
#include "eval/frame_comparison.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/scene_resources.h"

namespace relief {
namespace {

Frame median_frame(const Scene& scene, const SceneResources& resources, Backend backend, int repeat,
                   int threads, double& median_ms) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  FrameRequest request;
  request.backend = backend;
  request.outputs = {true, true, true, true, true, true};
  return render_frame_repeated(scene, resources, request, repeat, median_ms);
}

int run(int argc, char** argv) {
  const int repeat = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<std::string> presets;
  for (int a = 2; a < argc; ++a) {
    presets.push_back(argv[a]);
  }
  if (presets.empty()) {
    presets = preset_names();
  }
  std::printf("GL: %s\n", gl_renderer().c_str());
  const int all = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  std::printf("%-8s %9s %9s %9s %7s | %8s %10s %10s %9s | %9s %9s %9s %6s %8s\n", "preset",
              "simd 2T", "simd all", "gl", "gl/2T", "invalid", "height/A", "normal deg", "nu",
              "visib. %", "depth", "normal deg", "sRGB", "PSNR dB");
  for (const std::string& preset : presets) {
    const Scene scene = resolve_scene(preset, {});
    const SceneResources resources = load_scene_resources(scene);
    double cpu2 = 0, cpu_all = 0, gl_ms = 0;
    const Frame cpu = median_frame(scene, resources, Backend::kSimd, repeat, 2, cpu2);
    median_frame(scene, resources, Backend::kSimd, repeat, all, cpu_all);
    const Frame gl = median_frame(scene, resources, Backend::kGl, repeat, all, gl_ms);
    const GridDifference grid =
        compare_grids(run_terrain_stages<float>(scene, resources.lattice, Backend::kReference,
                                                resources.sketch_or_null())
                          .grid,
                      gl_terrain_stages(scene, resources.lattice, resources.sketch_or_null()));
    const PixelDifference pixels = compare_pixels(cpu.image, gl.image);
    std::printf(
        "%-8s %9.2f %9.2f %9.2f %7.2f | %8llu %10.3g %10.3g %9.3g | %9.4f %9.3g %9.3g %6.0f "
        "%8.2f\n",
        preset.c_str(), cpu2, cpu_all, gl_ms, gl_ms / cpu2,
        static_cast<unsigned long long>(grid.valid_mismatch),  // NOLINT(runtime/int)
        grid.max_height_error / scene.terrain.amplitude, grid.max_normal_angle_deg,
        grid.max_octave_error, 100 * pixels.visibility_share(), pixels.max_depth_error,
        pixels.max_normal_angle_deg, pixels.max_srgb_error, pixels.srgb_psnr);
  }
  return 0;
}

}  // namespace
}  // namespace relief

int main(int argc, char** argv) {
  try {
    return relief::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relief_gl_frame_report: %s\n", e.what());
    return 2;
  }
}
