// The first image: the projected grid rasterised as a closed surface, with no holes at the
// viewport borders and no cracks, for a set of cameras.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/shade.h"
#include "core/shading_plan.h"
#include "pipeline/frame.h"
#include "raster/resolve.h"
#include "tests/oracles/whole_frame.h"

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
      // The projector's refinement by the regional height bound (core/projector.h): high
      // above looking down, just above the terrain, far from the origin, and the presets.
      {"high, pitch -60", {"camera.pitch_deg=-60", "camera.position=[0, 12000, 0]"}},
      {"high, pitch -90", {"camera.pitch_deg=-90", "camera.position=[0, 12000, 0]"}},
      {"just above the terrain", {"camera.pitch_deg=-5", "camera.position=[0, 120, 0]"}},
      {"1e6 from the origin", {"camera.position=[600000, 700, -800000]"}},
      {"1e6 high",
       {"camera.pitch_deg=-90", "camera.position=[0, 1000000, 0]", "camera.far=1000000000"}},
  };
  const std::vector<std::string> presets = {"lava", "dunes", "lake", "plain"};
  std::vector<std::pair<std::string, CameraCase>> runs;
  for (const CameraCase& c : cases) {
    runs.emplace_back("default", c);
  }
  for (const std::string& preset : presets) {
    runs.emplace_back(preset, CameraCase{preset, {}});
  }
  for (const auto& [preset, c] : runs) {
    std::vector<std::string> overrides = {"viewport.width=320", "viewport.height=256",
                                          "grid.width=160", "grid.height=160"};
    overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
    const Scene scene = resolve_scene(preset, overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const TerrainFrame frame = rasterize_terrain(scene, lattice);
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
  const SceneResources resources = load_scene_resources(scene);
  FrameRequest request;
  request.outputs.linear = true;
  const FrameImage reference = render_frame(scene, resources, request).image;
  for (int threads : {1, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const FrameImage image = render_frame(scene, resources, request).image;
    CHECK(image.srgb == reference.srgb);
    CHECK(image.linear == reference.linear);
  }
}

TEST_CASE("everyPresetRendersWithoutNanOrInfinity", "[render]") {
  for (const std::string& preset : preset_names()) {
    const Scene scene = resolve_scene(
        preset, {"viewport.width=192", "viewport.height=144", "grid.width=96", "grid.height=96"});
    const SceneResources resources = load_scene_resources(scene);
    FrameRequest request;
    request.outputs.linear = true;
    const FrameImage image = render_frame(scene, resources, request).image;
    INFO(preset);
    REQUIRE(image.linear.size() == 192u * 144u * 3u);
    int covered = 0;
    for (std::size_t k = 0; k < image.linear.size(); ++k) {
      REQUIRE(std::isfinite(image.linear[k]));
      REQUIRE(image.linear[k] >= 0.0f);
    }
    const TerrainFrame frame = rasterize_terrain(scene, resources);
    for (std::uint32_t p : frame.visibility.primitive) {
      covered += p != raster::kNoPrimitive;
    }
    CHECK(covered > 192 * 144 / 5);  // every preset shows terrain
  }
}

TEST_CASE("waterCoversOnlyPixelsBelowTheWaterLevel", "[render]") {
  const Scene scene = resolve_scene(
      "lake", {"viewport.width=160", "viewport.height=120", "grid.width=96", "grid.height=96"});
  const SceneResources resources = load_scene_resources(scene);
  const TerrainFrame frame = rasterize_terrain(scene, resources);
  const raster::ResolvedFrame r = resolve_for_shading(frame);
  const ShadingInputs in = shading_inputs(frame, r);
  const ShadeParams<float> with_water =
      make_shade_params<float>(make_shading_plan(scene, frame.plan, resources.lattice.size));
  ShadeParams<float> without_water = with_water;
  without_water.water_enabled = 0;
  const ShadeResources shade_resources{&resources.lattice, resources.textures};
  std::vector<float> a(160 * 120 * 3), b(a.size());
  shade_pixels<float>(with_water, shade_resources, in, RowRange{0, 120}, a);
  shade_pixels<float>(without_water, shade_resources, in, RowRange{0, 120}, b);
  int wet = 0, dry = 0;
  for (std::size_t k = 0; k < 160 * 120; ++k) {
    if (frame.visibility.primitive[k] == raster::kNoPrimitive) {
      continue;
    }
    const bool above =
        r.value[2][k] >= float(*scene.terrain.water_level - scene.camera.position[1]);
    const bool same =
        a[3 * k] == b[3 * k] && a[3 * k + 1] == b[3 * k + 1] && a[3 * k + 2] == b[3 * k + 2];
    if (above) {
      ++dry;
      REQUIRE(same);
    } else {
      ++wet;
      CHECK_FALSE(same);
    }
  }
  CHECK(wet > 100);
  CHECK(dry > 100);
}

}  // namespace
}  // namespace relief
