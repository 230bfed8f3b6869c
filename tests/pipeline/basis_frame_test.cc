// §3 Eq. 2's basis images in whole frames: stage 3 reads the composed grid (and the shading
// the noise lattice still), the fractal stays within the height bounds the grid's extremes
// give, and the presets that use them. Backend agreement: the basis presets are in the preset
// lists of tests/simd/simd_test.cc and tests/gl/gl_terrain_test.cc.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"

namespace relief {
namespace {

TEST_CASE("theFractalOnBasisImagesStaysWithinTheBoundsOfTheComposedGrid", "[basis]") {
  const std::vector<std::pair<const char*, std::vector<std::string>>> cases = {
      {"craters", {}},
      {"badlands", {}},
      // From high above, over many tiles, mirrored and filtered, with the warp.
      {"badlands",
       {"camera.position=[3000,9000,-2000]", "camera.pitch_deg=-60",
        "terrain.basis.wrap=\"mirror\"",
        "terrain.basis.images=[{\"image\":\"builtin:basis/ridges\",\"weight\":0.5,"
        "\"high_pass\":20,\"normalize\":true},{\"image\":\"builtin:basis/craters\","
        "\"weight\":\"builtin:basis/dunes\",\"low_pass\":1.5}]",
        "terrain.warp.enabled=true"}},
  };
  for (const auto& [preset, overrides] : cases) {
    std::vector<std::string> sets = {"grid.width=96", "grid.height=96"};
    sets.insert(sets.end(), overrides.begin(), overrides.end());
    const Scene scene = resolve_scene(preset, sets);
    const SceneResources resources = load_scene_resources(scene);
    REQUIRE(resources.basis);
    const NoiseLattice& grid = *resources.basis;
    INFO(preset << " " << grid.size);
    const TerrainRun<float> run =
        run_terrain_stages<float>(scene, resources.terrain_values(), Backend::kReference);
    // The bounds come from the composed grid's extremes (height_bounds.h).
    double amplitude_sum = 0.0;
    for (int k = scene.terrain.first_octave; k <= scene.terrain.last_octave; ++k) {
      amplitude_sum += std::pow(scene.terrain.r, -k * scene.terrain.H);
    }
    CHECK(run.plan.bounds.fbm_max == amplitude_sum * std::max(0.0, double(grid.max_value)));
    CHECK(run.plan.bounds.fbm_min == amplitude_sum * std::min(0.0, double(grid.min_value)));
    CHECK(run.plan.terrain.lattice == &grid);
    CHECK(run.plan.terrain.inv_horizontal_scale ==
          1.0 / (scene.terrain.basis->tile_size / grid.size));
    std::size_t valid = 0, outside = 0;
    const double camera_y = scene.camera.position[1];
    for (std::size_t k = 0; k < run.plan.layout.size(); ++k) {
      if (run.grid.valid[k]) {
        const double h = run.grid.height[k] + camera_y;
        ++valid;
        outside += !(h >= run.plan.bounds.world_min && h <= run.plan.bounds.world_max);
      }
    }
    CHECK(valid > 1000);
    CHECK(outside == 0);
  }
}

TEST_CASE("aBasisSceneRendersItsImagesWhileTheShadingKeepsTheNoiseLattice", "[basis]") {
  const std::vector<std::string> small = {"viewport.width=96", "viewport.height=64",
                                          "grid.width=48", "grid.height=48"};
  const Scene craters = resolve_scene("craters", small);
  const SceneResources resources = load_scene_resources(craters);
  // The noise lattice is still there, built from the scene's seed and lattice_size.
  CHECK(resources.lattice.size == craters.terrain.lattice_size);
  CHECK(resources.basis->size == 256 * craters.terrain.basis->upsample);
  FrameRequest request;
  request.backend = Backend::kReference;
  const Frame with = render_frame(craters, resources, request);
  std::vector<std::string> none = small;
  none.push_back("terrain.basis=null");
  const Scene plain = resolve_scene("craters", none);
  const Frame without = render_frame(plain, load_scene_resources(plain), request);
  CHECK(with.image.srgb != without.image.srgb);
  // Deterministic: the same scene again gives the same bytes.
  CHECK(render_frame(craters, load_scene_resources(craters), request).image.srgb ==
        with.image.srgb);
}

}  // namespace
}  // namespace relief
