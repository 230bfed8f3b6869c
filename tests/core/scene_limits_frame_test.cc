// Frames at the bounds of core/limits.h (docs/scene-limits.md): a small frame rendered with a
// field at each of its bounds has finite, non-negative radiance, finite stage buffers and,
// where the view allows it, terrain on a fair share of the pixels; and the cases of the issue
// that asked for these bounds (tile_size = 1e-36, tiny camera.near, horizontal_scale, H and
// dither_scale), which also show what breaks without the bound. The refusals just outside each
// bound and the derivations: tests/core/scene_limits_test.cc.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "raster/resolve.h"
#include "tests/core/scene_limits_support.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;
using test::scene_limits::above;
using test::scene_limits::below;
using test::scene_limits::cat;
using test::scene_limits::error_of;
using test::scene_limits::FrameCheck;
using test::scene_limits::kSmallFrame;
using test::scene_limits::render_scene;
using test::scene_limits::render_small;

// A field at one of its bounds, with the few other fields a rule across fields needs.
struct BoundCase {
  std::vector<std::string> set;
  bool shows_terrain;  // the view of the default camera still meets the terrain
};

// Each field at its lower and at its upper bound.
std::vector<BoundCase> bound_cases() {
  const std::string wide = "viewport.width=16384";
  return {
      {{"camera.position=[-1e12, 700, -1e12]"}, true},
      {{"camera.position=[1e12, 700, 1e12]"}, true},
      {{"camera.position=[0, -1e12, 0]"}, false},  // the terrain is beyond camera.far
      {{"camera.position=[0, 1e12, 0]"}, false},
      {{"camera.yaw_deg=-360"}, true},
      {{"camera.yaw_deg=360"}, true},
      {{"camera.pitch_deg=-90"}, true},
      {{"camera.pitch_deg=90"}, false},  // straight up
      {{"camera.look_at=[-1e12, -1e12, -1e12]"}, true},
      {{"camera.look_at=[1e12, 1e12, 1e12]"}, false},
      {{"camera.fov_y_deg=1"}, true},
      {{"camera.fov_y_deg=170"}, true},
      {{"camera.near=1e-17"}, true},
      {{cat({"camera.near=", format_number(below(60000))})}, false},  // clips all but the far
      {{cat({"camera.far=", format_number(above(0.5))})}, false},     // just beyond near
      {{"camera.far=1e9"}, true},
      {{"viewport.width=1"}, true},
      {{wide, "viewport.height=8", "camera.fov_y_deg=1"}, true},  // horizontal fov <= 175
      {{"viewport.height=1", "viewport.width=8"}, true},
      {{"viewport.height=16384", "viewport.width=16", "camera.fov_y_deg=170"}, true},
      {{"grid.width=2", "grid.margin=0"}, true},
      {{"grid.width=8192"}, true},
      {{"grid.height=2", "grid.margin=0"}, true},
      {{"grid.height=8192"}, true},
      {{"grid.margin=0"}, true},
      {{"grid.margin=64", "grid.width=130", "grid.height=130"}, true},
      {{"terrain.seed=0"}, true},
      {{"terrain.seed=18446744073709551615"}, true},
      {{"terrain.lattice_size=4"}, true},
      {{"terrain.lattice_size=4096"}, true},
      {{"terrain.r=1.001"}, true},
      {{"terrain.r=16", "terrain.last_octave=10"}, true},
      {{"terrain.H=0.00025", "terrain.r=16", "terrain.last_octave=10"}, true},
      {{"terrain.H=0.0009765625"}, true},  // the amplitude rule's bound at r = 2
      {{"terrain.H=1"}, true},
      {{"terrain.first_octave=0"}, true},
      {{"terrain.first_octave=32", "terrain.last_octave=32", "terrain.horizontal_scale=1e8"}, true},
      {{"terrain.last_octave=0"}, true},
      {{"terrain.first_octave=32", "terrain.last_octave=55", "terrain.r=1.6",
        "terrain.horizontal_scale=1e6"},
       true},
      {{"terrain.lod.bias=-8"}, true},
      {{"terrain.lod.bias=8"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c1=[-100, -100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c1=[100, 100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c2=[-100, -100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c2=[100, 100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c3=[-100, -100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.c3=[100, 100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.r0=[-100, -100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.r0=[100, 100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.t0=[-100, -100]"}, true},
      {{"terrain.warp.enabled=true", "terrain.warp.t0=[100, 100]"}, true},
      {{"terrain.horizontal_scale=0.01"}, true},  // the bound across fields for this view
      {{"terrain.horizontal_scale=1e9"}, true},
      {{"terrain.base_height=-1e7"}, false},  // 1e7 below the camera: beyond camera.far
      {{"terrain.base_height=1e7"}, false},   // the camera deep inside the terrain
      {{"terrain.amplitude=1e-25"}, true},
      {{"terrain.amplitude=1e7"}, false},  // the camera inside the mountains
      {{"terrain.water_level=-1e7"}, true},
      {{"terrain.water_level=1e7"}, true},
      {{"shading.layers.3.tile_size=1e-4"}, true},
      {{"shading.layers.3.tile_size=1e6"}, true},
      {{"shading.layers.2.height=[-1e7, -9999999]"}, true},
      {{"shading.layers.2.height=[9999999, 1e7]"}, true},
      {{"shading.layers.2.height_spread=0"}, true},
      {{"shading.layers.2.height_spread=1e6"}, true},
      {{"shading.layers.2.slope_deg=[0, 0.001]"}, true},
      {{"shading.layers.2.slope_deg=[89.999, 90]"}, true},
      {{"shading.layers.2.slope_spread_deg=0"}, true},
      {{"shading.layers.2.slope_spread_deg=45"}, true},
      {{"shading.layers.4.specular=0"}, true},
      {{"shading.layers.4.specular=1"}, true},
      {{"shading.texture_size=16"}, true},
      {{"shading.texture_size=2048", R"(shading.layers=[{"texture": "builtin:snow"}])"}, true},
      {{"shading.mip_blend=0"}, true},
      {{"shading.mip_blend=1"}, true},
      {{"shading.dither=0"}, true},
      {{"shading.dither=4"}, true},
      {{"shading.dither_scale=0.01"}, true},
      {{"shading.dither_scale=1e-26"}, true},
      {{"shading.dither_scale=1e6"}, true},
      {{"lighting.sun_azimuth_deg=-360"}, true},
      {{"lighting.sun_azimuth_deg=360"}, true},
      {{"lighting.sun_elevation_deg=-90"}, true},
      {{"lighting.sun_elevation_deg=90"}, true},
      {{"lighting.sun_color=[0, 0, 0]"}, true},
      {{"lighting.sun_color=[1000, 1000, 1000]"}, true},
      {{"lighting.sun_intensity=0"}, true},
      {{"lighting.sun_intensity=1000"}, true},
      {{"lighting.sky_color=[0, 0, 0]"}, true},
      {{"lighting.sky_color=[1000, 1000, 1000]"}, true},
      {{"lighting.ground_color=[0, 0, 0]"}, true},
      {{"lighting.ground_color=[1000, 1000, 1000]"}, true},
      {{"lighting.sky_intensity=0"}, true},
      {{"lighting.sky_intensity=1000"}, true},
      {{"lighting.ambient=0"}, true},
      {{"lighting.ambient=1000"}, true},
      {{"lighting.shininess=1"}, true},
      {{"lighting.shininess=10000"}, true},
      {{"lighting.exposure=1e-11"}, true},
      {{"lighting.exposure=1000"}, true},
      {{"water.shallow_color=[0, 0, 0]"}, true},
      {{"water.shallow_color=[1, 1, 1]"}, true},
      {{"water.deep_color=[0, 0, 0]"}, true},
      {{"water.deep_color=[1, 1, 1]"}, true},
      {{"water.extinction=[0, 0, 0]"}, true},
      {{"water.extinction=[100, 100, 100]"}, true},
      {{"water.full_depth=1e-26"}, true},
      {{"water.full_depth=1e6"}, true},
      {{"water.wave_length=1e-26"}, true},
      {{"water.wave_length=1e6"}, true},
      {{"water.wave_strength=0"}, true},
      {{"water.wave_strength=10"}, true},
      {{"water.wave_speed=0"}, true},
      {{"water.wave_speed=1e6"}, true},
      {{"sky.zenith_color=[0, 0, 0]"}, true},
      {{"sky.zenith_color=[1000, 1000, 1000]"}, true},
      {{"sky.horizon_color=[0, 0, 0]"}, true},
      {{"sky.horizon_color=[1000, 1000, 1000]"}, true},
      {{"sky.sun_disc_deg=0.11"}, true},
      {{"sky.sun_disc_deg=10"}, true},
      {{"sky.fog_density=0"}, true},
      {{"sky.fog_density=1"}, true},
      {{"sky.atmosphere.scale_height=10"}, true},
      {{"sky.atmosphere.scale_height=1e6"}, true},
      {{"sky.atmosphere.rayleigh=[0, 0, 0]", "sky.atmosphere.mie=0",
        "sky.atmosphere.absorption=[0, 0, 0]"},
       true},
      {{"sky.atmosphere.rayleigh=[0.01, 0.01, 0.01]", "sky.atmosphere.mie=0.01",
        "sky.atmosphere.absorption=[0.01, 0.01, 0.01]"},
       true},
      {{"sky.atmosphere.mie_g=0"}, true},
      {{"sky.atmosphere.mie_g=0.95", "sky.atmosphere.intensity=1000"}, true},
      {{"sky.atmosphere.intensity=0"}, true},
      {{"time=-1e9"}, true},
      {{"time=1e9"}, true},
  };
}

TEST_CASE("everyNumericFieldRendersFiniteNonNegativeFramesAtBothOfItsBounds", "[limits]") {
  for (const BoundCase& c : bound_cases()) {
    std::string label;
    for (const std::string& s : c.set) {
      label.append(" --set ").append(s);
    }
    INFO(label);
    const FrameCheck f = render_small(c.set);
    CHECK(f.bad_radiance == 0);
    CHECK(f.bad_buffers == 0);
    if (c.shows_terrain) {
      CHECK(f.covered >= f.pixels / 10);
    }
  }
}

// --- The issue's cases ---------------------------------------------------------------------

TEST_CASE("issueCaseTileSize1e-36IsRefusedAndTheSmallestAllowedTileRendersFinite", "[limits]") {
  CHECK_THAT(error_of({"shading.layers.3.tile_size=1e-36"}),
             Contains("shading.layers[3].tile_size = 1e-36 is out of range; allowed 1e-04 <= "
                      "shading.layers[3].tile_size <= 1e+06"));
  // Every layer at the smallest tile: GL's LOD stays within its log's domain everywhere.
  std::vector<std::string> set;
  for (int k = 0; k < 5; ++k) {
    set.push_back(cat({"shading.layers.", std::to_string(k), ".tile_size=1e-4"}));
  }
  const FrameCheck f = render_small(set);
  CHECK(f.bad_radiance == 0);
  CHECK(f.bad_buffers == 0);
  CHECK(f.covered >= f.pixels / 10);
}

TEST_CASE("issueCaseTinyCameraNearIsRefusedAndTheSmallestAllowedNearStillShowsTheTerrain",
          "[limits]") {
  for (const char* tiny : {"camera.near=1e-30", "camera.near=1e-40", "camera.near=5e-324"}) {
    INFO(tiny);
    CHECK_THAT(error_of({tiny}),
               Contains("is out of range; allowed 1e-17 <= camera.near <= 1e+09"));
  }
  const FrameCheck reference = render_small(std::vector<std::string>{});
  const FrameCheck f = render_small({"camera.near=1e-17"});
  CHECK(f.bad_radiance == 0);
  CHECK(f.bad_buffers == 0);
  CHECK(f.covered == reference.covered);
  // Without the bound: at 1e-39 (a subnormal float) the clip-space z = near and the depth
  // near / w are no longer normal floats, and the depth test drops every triangle.
  Scene scene = resolve_scene("default", kSmallFrame);
  scene.camera.near = 1e-39;
  CHECK(render_scene(scene).covered == 0);
}

TEST_CASE("issueCaseTinyHorizontalScaleIsRefusedAndTheSmallestAllowedScaleStillVaries",
          "[limits]") {
  CHECK_THAT(error_of({"terrain.horizontal_scale=1e-30"}),
             Contains("terrain.horizontal_scale = 1e-30 is out of range; allowed 1e-15 <= "
                      "terrain.horizontal_scale <= 1e+09"));
  CHECK_THAT(error_of({"terrain.horizontal_scale=1e-6"}),
             Contains("allowed terrain.horizontal_scale >= "));
  const auto distinct = [](const std::vector<float>& v) {
    return std::set<float>(v.begin(), v.end()).size();
  };
  // One octave, so that a height depends on the lattice alone (not on the LOD weights).
  const FrameCheck f = render_small({"terrain.horizontal_scale=0.01", "terrain.last_octave=0"});
  CHECK(f.bad_radiance == 0);
  CHECK(f.bad_buffers == 0);
  CHECK(distinct(f.heights) > f.heights.size() / 2);  // noise, not a constant
  // Without the bound the lattice coordinates pass 2^24 P: the wrap returns cell 0 for every
  // vertex, and the terrain is one flat plane.
  std::vector<std::string> set = kSmallFrame;
  set.push_back("terrain.last_octave=0");
  Scene scene = resolve_scene("default", set);
  scene.terrain.horizontal_scale = 1e-30;
  CHECK(distinct(render_scene(scene).heights) == 1);
}

// nu = clamp(c0 - c1 log2_det(sigma^2), 1, N) as stage 2 evaluates it in float, against the
// same formula in double on the same sigma^2: the largest difference over the spacings where
// nu is in range (and above kMinSpacingSq, below which stage 2 takes no log).
double worst_float_nu_error(const TerrainSettings& terrain) {
  const LodPlan lod = make_lod_plan(terrain);
  const float c0 = float(lod.c0), c1 = float(lod.c1), nu_max = float(lod.nu_max);
  const double from = std::max(std::log2(limits::kMinSpacingSq), (lod.c0 - lod.nu_max) / lod.c1);
  const double to = (lod.c0 - 1) / lod.c1;
  double worst = 0;
  int in_range = 0;
  for (int k = 0; k <= 20000; ++k) {
    const float spacing_sq = float(std::exp2(from + (to - from) * k / 20000));
    const double exact = lod.c0 - lod.c1 * std::log2(double(spacing_sq));
    if (exact < 1 || exact > lod.nu_max) {
      continue;
    }
    const float nu = std::clamp(c0 - c1 * log2_det(spacing_sq), 1.0f, nu_max);
    worst = std::max(worst, std::abs(double(nu) - exact));
    ++in_range;
  }
  CHECK(in_range > 10000);
  return worst;
}

TEST_CASE("issueCaseTinyHurstExponentIsRefusedAndTheSmallestAllowedKeepsFloatNuAccurate",
          "[limits]") {
  CHECK_THAT(error_of({"terrain.H=1e-30"}),
             Contains("terrain.H = 1e-30 is out of range; allowed 0.00025 <= terrain.H <= 1"));
  CHECK_THAT(error_of({"terrain.H=0.0005"}),
             Contains("allowed terrain.H * log2(terrain.r) >= 0.0009765625"));
  // At the bound (c1 = 512) float keeps nu within 1/256 octave of the exact formula, for
  // amplitudes that put the in-range part anywhere in the spacings a frame can have.
  TerrainSettings t;
  t.H = 0x1p-10;
  for (const double amplitude : {360.0, 0x1p-49, 1e7}) {
    t.amplitude = amplitude;
    INFO("amplitude " << amplitude);
    CHECK(worst_float_nu_error(t) <= 1.0 / 256);
  }
  const FrameCheck f = render_small({"terrain.H=0.0009765625"});
  CHECK(f.bad_radiance == 0);
  CHECK(f.bad_buffers == 0);
  for (float nu : f.nu) {
    REQUIRE(nu >= 1.0f);
    REQUIRE(nu <= 15.0f);
  }
  // Beyond it the error grows with c1: at four times the gain it is twice the step.
  t.H = 0x1p-12;
  t.amplitude = 0x1p-49;
  CHECK(worst_float_nu_error(t) > 1.0 / 256);
  // And without any bound c1 overflows float: nu becomes NaN in stage 2's buffer.
  Scene scene = resolve_scene("default", kSmallFrame);
  scene.terrain.H = 1e-300;
  CHECK(render_scene(scene).bad_buffers > 0);
}

TEST_CASE("issueCaseTinyDitherScaleIsRefusedAndTheSmallestAllowedRendersFinite", "[limits]") {
  CHECK_THAT(error_of({"shading.dither_scale=1e-30"}),
             Contains("shading.dither_scale = 1e-30 is out of range; allowed 1e-26 <= "
                      "shading.dither_scale <= 1e+06"));
  // The smallest allowed scale, and one whose noise cells the near pixels still resolve: the
  // noise is sampled only where it is coarser than the pixels, so both render finite.
  for (const char* scale : {"shading.dither_scale=1e-26", "shading.dither_scale=0.01"}) {
    const FrameCheck f = render_small({scale, "shading.dither=4"});
    CHECK(f.bad_radiance == 0);
    CHECK(f.bad_buffers == 0);
    CHECK(f.covered >= f.pixels / 10);
  }
}
}  // namespace
}  // namespace relief
