// Where the projected grid's triangles go (§4.1, "near-optimal sampling"): for each preset and
// a set of cameras, the triangles submitted and set up by the rasteriser (front-facing, on
// screen: the share of the grid spent on what is seen), and per band of grid rows the share
// of triangles that are on screen and front-facing, classified from their clip coordinates.
// Also the nearest and farthest horizontal distance of a valid vertex, and the frame plan's
// time (the projector's refinement runs in it).
// Run: build/bench/relief_projector_report [grid side, default 512]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

struct Case {
  const char* preset;
  const char* camera;
  std::vector<std::string> overrides;
};

std::vector<Case> cases() {
  std::vector<Case> list;
  for (const char* preset : {"default", "alpine", "lava", "dunes", "lake", "plain"}) {
    list.push_back({preset, "preset", {}});
  }
  list.push_back(
      {"default", "high, pitch -60", {"camera.position=[0, 12000, 0]", "camera.pitch_deg=-60"}});
  list.push_back(
      {"default", "high, pitch -90", {"camera.position=[0, 12000, 0]", "camera.pitch_deg=-90"}});
  list.push_back(
      {"default", "just above terrain", {"camera.position=[0, 120, 0]", "camera.pitch_deg=-5"}});
  list.push_back({"default", "1e6 from origin", {"camera.position=[600000, 700, -800000]"}});
  list.push_back(
      {"default",
       "1e6 high, pitch -90",
       {"camera.position=[0, 1000000, 0]", "camera.pitch_deg=-90", "camera.far=1000000000"}});
  return list;
}

// Triangle t of the grid (raster/topology.h): on screen (not wholly outside one clip plane)
// and front-facing (counter-clockwise in window coordinates; a triangle crossing w = 0 counts
// as front-facing, the rasteriser clips it).
bool seen(const TerrainFrame& f, const std::uint32_t v[3]) {
  const float* x[4] = {f.clip_x.data(), f.clip_y.data(), f.clip_z.data(), f.clip_w.data()};
  int out[6] = {};
  bool positive_w = true;
  double px[3], py[3];
  for (int k = 0; k < 3; ++k) {
    const double cx = x[0][v[k]], cy = x[1][v[k]], cz = x[2][v[k]], cw = x[3][v[k]];
    out[0] += cx < -cw;
    out[1] += cx > cw;
    out[2] += cy < -cw;
    out[3] += cy > cw;
    out[4] += cz > cw;  // nearer than the near plane (reverse-Z)
    out[5] += cw <= 0;
    positive_w = positive_w && cw > 0;
    px[k] = cw > 0 ? cx / cw : 0;
    py[k] = cw > 0 ? cy / cw : 0;
  }
  for (const int o : out) {
    if (o == 3) {
      return false;
    }
  }
  if (!positive_w) {
    return true;
  }
  return (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]) > 0;
}

void report(const Case& c, int grid) {
  std::vector<std::string> overrides = c.overrides;
  overrides.push_back("grid.width=" + std::to_string(grid));
  overrides.push_back("grid.height=" + std::to_string(grid));
  const Scene scene = resolve_scene(c.preset, overrides);
  const SceneResources resources = load_scene_resources(scene);
  const auto start = std::chrono::steady_clock::now();
  const FramePlan plan = make_frame_plan(scene, resources.lattice, resources.sketch_or_null());
  const double plan_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const Frame frame = render_frame(scene, resources, FrameRequest{});
  const raster::RasterStats& s = frame.stats.raster;
  const TerrainFrame f = rasterize_terrain(scene, resources);
  constexpr int kBands = 8;
  std::uint64_t drawn[kBands] = {}, total[kBands] = {};
  const raster::GridTriangles triangles = f.triangles();
  const int rows = f.plan.layout.height - 1;
  for (std::uint32_t t = 0; t < triangles.count(); ++t) {
    std::uint32_t v[3];
    const int band =
        static_cast<int>((t >> 1) / std::uint32_t(f.plan.layout.width - 1)) * kBands / rows;
    ++total[band];
    if (triangles.vertices(t, v) && seen(f, v)) {
      ++drawn[band];
    }
  }
  double nearest = 1e300, farthest = 0;
  for (std::size_t k = 0; k < f.grid.layout.size(); ++k) {
    if (f.grid.valid[k]) {
      const double d = std::hypot(double(f.grid.dx[k]), double(f.grid.dz[k]));
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
    }
  }
  std::printf("%-8s %-20s %8llu %8llu %5.1f%%  near %8.1f far %9.0f  plan %5.2f ms  bands:",
              c.preset, c.camera, static_cast<unsigned long long>(s.triangles),
              static_cast<unsigned long long>(s.setup),
              s.triangles ? 100.0 * double(s.setup) / double(s.triangles) : 0.0, nearest, farthest,
              plan_ms);
  for (int b = 0; b < kBands; ++b) {
    std::printf(" %3.0f", total[b] ? 100.0 * double(drawn[b]) / double(total[b]) : 0.0);
  }
  std::printf("\n");
}

}  // namespace
}  // namespace relief

int main(int argc, char** argv) {
  const int grid = argc > 1 ? std::atoi(argv[1]) : 512;
  std::printf(
      "scene    camera               submitted set up  share  (valid vertices' "
      "horizontal distance)  per eighth of the grid rows, near to far: %% seen\n");
  for (const relief::Case& c : relief::cases()) {
    relief::report(c, grid);
  }
  return 0;
}
