#include <algorithm>
#include <chrono>
#include <iomanip>
#include <ostream>
#include <vector>

#include "pipeline/image_io.h"
#include "pipeline/job_memory.h"
#include "pipeline/render_frame.h"
#include "pipeline/statistics.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/commands.h"

namespace relief {

int run_render_command(const Scene& scene, const RenderOptions& options, std::ostream& out) {
  const std::string path = options.output.empty() ? scene.output.image : options.output;
  const std::string float_path =
      options.float_output.empty() ? scene.output.float_image.value_or("") : options.float_output;
  const MemoryEstimate estimate = estimate_render_memory(scene, !float_path.empty());
  check_memory(estimate, options.budget, "this render",
               "Lower viewport.width/height or grid.width/height");
  const raster::RasterLimits limits{memory_left(estimate, options.budget)};
  const auto setup_start = std::chrono::steady_clock::now();
  const SceneResources resources = load_scene_resources(scene);  // validates texture files
  const double setup_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - setup_start)
          .count();
  RenderedImage image;
  std::vector<FrameTimings> runs;
  for (int run = 0; run < options.repeat; ++run) {
    FrameTimings timings;
    image = render_frame(scene, resources, timings, limits);
    runs.push_back(timings);
  }
  OutputSet files;  // the image and the float image appear together or not at all
  files.add(path, encode_png_rgb(image.width, image.height, image.rgb));
  if (!float_path.empty()) {
    files.add(float_path,
              encode_pfm(image.width, image.height, 3, image.linear, std::size_t(image.width) * 3));
  }
  files.commit();
  auto stage = [&](const char* name, auto field) {
    std::vector<double> values;
    for (const FrameTimings& t : runs) {
      values.push_back(field(t));
    }
    out << "  " << std::left << std::setw(28) << name << std::right << std::setw(9)
        << median(values) << " ms\n";
  };
  out << std::fixed << std::setprecision(3) << image.width << "x" << image.height << " image, "
      << scene.grid.width << "x" << scene.grid.height << " grid, median of " << options.repeat
      << " run(s):\n";
  stage("stage 1-2 projected domain",
        [](const FrameTimings& t) { return t.terrain.projected_domain_ms; });
  stage("stage 3   fractal", [](const FrameTimings& t) { return t.terrain.fbm_ms; });
  stage("stage 4   surface", [](const FrameTimings& t) { return t.terrain.surface_ms; });
  stage("stage 5   vertex transform", [](const FrameTimings& t) { return t.transform_ms; });
  stage("stage 6   rasterisation", [](const FrameTimings& t) { return t.raster_ms; });
  stage("stage 7   resolve", [](const FrameTimings& t) { return t.resolve_ms; });
  stage("stage 8   shading", [](const FrameTimings& t) { return t.shade_ms; });
  stage("stage 9   sRGB encoding", [](const FrameTimings& t) { return t.encode_ms; });
  stage("total", [](const FrameTimings& t) {
    return t.terrain.projected_domain_ms + t.terrain.fbm_ms + t.terrain.surface_ms +
           t.transform_ms + t.raster_ms + t.resolve_ms + t.shade_ms + t.encode_ms;
  });
  const raster::RasterStats& s = runs.back().raster;
  out << "  scene set-up (lattice, textures, mip chains) " << setup_ms << " ms, once\n"
      << "  triangles submitted " << s.triangles << ", set up " << s.setup << "\n"
      << "wrote " << path << (float_path.empty() ? "" : " and " + float_path) << "\n";
  return kExitOk;
}

}  // namespace relief
