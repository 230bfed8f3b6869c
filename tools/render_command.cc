#include <algorithm>
#include <iomanip>
#include <ostream>
#include <vector>

#include "core/lattice.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "tools/render_frame.h"

namespace relief {

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

int run_render_command(const Scene& scene, const RenderOptions& options, std::ostream& out) {
  const std::string path = options.output.empty() ? scene.output.image : options.output;
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  RenderedImage image;
  std::vector<FrameTimings> runs;
  for (int run = 0; run < options.repeat; ++run) {
    FrameTimings timings;
    image = render_diagnostic_frame(scene, lattice, timings);
    runs.push_back(timings);
  }
  write_file_atomically(path, encode_png_rgb(image.width, image.height, image.rgb));
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
  stage("diagnostic shading", [](const FrameTimings& t) { return t.shade_ms; });
  const raster::RasterStats& s = runs.back().raster;
  out << "  triangles submitted " << s.triangles << ", set up " << s.setup << "\n"
      << "wrote " << path << "\n";
  return kExitOk;
}

}  // namespace relief
