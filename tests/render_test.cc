// The first image: the projected grid rasterised as a closed surface, with no holes at the
// viewport borders and no cracks, for a set of cameras.
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/lattice.h"
#include "core/scene_json.h"
#include "tools/render_frame.h"

namespace relief {
namespace {

struct CameraCase {
  std::string name;
  std::vector<std::string> overrides;
};

// Along every image column, a height field seen from above covers one run of pixels starting
// at the bottom row: a lower ray meets the terrain no later than a higher one. So any sky
// pixel below a terrain pixel is a hole (in the mesh, or at the border of the grid).
TEST_CASE("terrainImageHasNoHolesAtTheBordersAndNoCracks", "[render]") {
  const std::vector<CameraCase> cases = {
      {"default", {}},
      {"looking down", {"camera.pitch_deg=-50", "camera.position=[300, 1800, -200]"}},
      {"grazing", {"camera.pitch_deg=0", "camera.position=[0, 900, 0]"}},
      {"high", {"camera.pitch_deg=-25", "camera.position=[5000, 9000, 0]", "camera.yaw_deg=-120"}},
      {"lava", {"terrain.warp.enabled=true"}},
  };
  for (const CameraCase& c : cases) {
    std::vector<std::string> overrides = {"viewport.width=320", "viewport.height=256",
                                          "grid.width=160", "grid.height=160"};
    overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
    const Scene scene = resolve_scene("default", overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    FrameTimings timings;
    const TerrainFrame frame = rasterize_terrain(scene, lattice, timings);
    // The property needs the camera above the ground beneath it.
    REQUIRE(scene.camera.position[1] >
            fbm_height<double>(frame.plan.terrain, 0.0, 0.0, frame.plan.lod.nu_max));
    const raster::VisibilityBuffer& b = frame.visibility;
    int holes = 0, terrain = 0;
    for (int px = 0; px < b.width; ++px) {
      int top = -1;
      for (int py = 0; py < b.height; ++py) {
        if (b.primitive[b.index(px, py)] != raster::kNoPrimitive) {
          top = py;
        }
      }
      for (int py = 0; py <= top; ++py) {
        const bool covered = b.primitive[b.index(px, py)] != raster::kNoPrimitive;
        holes += !covered;
        terrain += covered;
      }
    }
    INFO("camera " << c.name << ": " << holes << " holes");
    CHECK(holes == 0);
    CHECK(terrain > b.width * b.height / 10);
    // The bottom row is the ground in front of the camera: all of it covered.
    for (int px = 0; px < b.width; ++px) {
      CHECK(b.primitive[b.index(px, 0)] != raster::kNoPrimitive);
    }
  }
}

TEST_CASE("renderedImageIsIdenticalForEveryThreadCount", "[render]") {
  const Scene scene = resolve_scene(
      "lava", {"viewport.width=200", "viewport.height=160", "grid.width=120", "grid.height=120"});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  FrameTimings timings;
  const RenderedImage reference = render_diagnostic_frame(scene, lattice, timings);
  for (int threads : {1, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    CHECK(render_diagnostic_frame(scene, lattice, timings).rgb == reference.rgb);
  }
}

}  // namespace
}  // namespace relief
