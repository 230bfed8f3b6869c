// Gradient shading (shading.mode = gradient, core/gradient_shade.h): the scene's fields and
// their refusals, the gradient and the Gouraud light against transcriptions of their
// definitions in double, each vertex's Lambert term, and whole frames: the light of every
// pixel lies within its triangle's vertex lights (interpolated, not recomputed per pixel), no
// texture is built or fetched, and the fused frame equals the unfused oracle's.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/gradient_shade.h"
#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "core/terrain_stages.h"
#include "core/vertex_culling.h"
#include "core/vertex_transform.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "raster/topology.h"
#include "tests/oracles/whole_frame.h"
#include "tests/support/frame_counters.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

const std::vector<std::string> kGradientFrame = {"viewport.width=160", "viewport.height=120",
                                                 "grid.width=96", "grid.height=80"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The gradient's definition in double: below the first stop its colour, above the last the
// last; between two stops of different heights linear; at a step (equal heights) the upper
// stop's colour from that height on.
std::array<double, 3> oracle_gradient(const std::vector<double>& height,
                                      const std::vector<std::array<double, 3>>& color, double h) {
  if (h < height.front()) {
    return color.front();
  }
  std::size_t i = height.size() - 1;
  while (i > 0 && height[i] > h) {
    --i;
  }
  // height[i] <= h < height[i + 1] (or i the last stop at or below h)
  if (i + 1 == height.size() || height[i + 1] == height[i]) {
    return color[i];
  }
  const double t = (h - height[i]) / (height[i + 1] - height[i]);
  std::array<double, 3> out{};
  for (int c = 0; c < 3; ++c) {
    out[c] = color[i][c] + (color[i + 1][c] - color[i][c]) * t;
  }
  return out;
}

template <class Real>
void check_gradient_against_oracle() {
  ShadeParams<Real> p;
  const std::vector<double> height = {-40, 0, 0, 120.5, 300, 300, 300, 910};
  const std::vector<std::array<double, 3>> color = {
      {0.1, 0.2, 0.3}, {0.2, 0.4, 0.9}, {0.7, 0.1, 0.0},  {0.3, 0.3, 0.3},
      {0.9, 0.8, 0.7}, {0.0, 0.5, 0.0}, {0.25, 0.5, 1.0}, {1.0, 1.0, 1.0}};
  ShadingPlan plan;
  plan.gradient.enabled = true;
  plan.gradient.height = height;
  for (const auto& c : color) {
    plan.gradient.color.push_back({c[0], c[1], c[2]});
  }
  p = make_shade_params<Real>(plan);
  REQUIRE(p.gradient_enabled == 1);
  REQUIRE(p.gradient_count == 8);
  test::TestRandom random(3);
  std::vector<double> samples = {-1e6,  -40,    -39.999, -1e-30, 0,  1e-30,
                                 120.5, 299.99, 300,     910,    1e9};
  for (int k = 0; k < 2000; ++k) {
    samples.push_back(random.uniform(-100, 1000));
  }
  for (const double h : samples) {
    const Vec3<Real> got = gradient_albedo(p, Real(h));
    const std::array<double, 3> want = oracle_gradient(height, color, double(Real(h)));
    INFO("height " << h);
    // float: the heights, the span's reciprocal and t each round once (a few ulps of 1).
    const double tolerance = std::is_same_v<Real, float> ? 4e-6 : 1e-14;
    CHECK(std::abs(double(got.x) - want[0]) <= tolerance);
    CHECK(std::abs(double(got.y) - want[1]) <= tolerance);
    CHECK(std::abs(double(got.z) - want[2]) <= tolerance);
  }
}

TEST_CASE("theHeightGradientIsPiecewiseLinearWithStepsAtRepeatedStops", "[gradient]") {
  check_gradient_against_oracle<float>();
  check_gradient_against_oracle<double>();
}

TEST_CASE("theGouraudLightIsTheSceneLightOfTheInterpolatedTerms", "[gradient]") {
  ShadingPlan plan;
  plan.light.sun = {1.8, 1.6, 1.4};
  plan.light.sky = {0.1, 0.15, 0.2};
  plan.light.ground = {0.05, 0.04, 0.03};
  plan.light.ambient = 0.03;
  const ShadeParams<double> p = make_shade_params<double>(plan);
  test::TestRandom random(5);
  for (int k = 0; k < 500; ++k) {
    const Vec3<double> albedo{random.uniform(0, 1), random.uniform(0, 1), random.uniform(0, 1)};
    const double lambert = random.uniform(0, 1), ny = random.uniform(-1, 1);
    const double share = random.uniform(0, 1);
    const double sky = k % 2 == 0 ? 1.0 : random.uniform(0, 1);  // sky light's open share
    const Vec3<double> got = gouraud_light(p, albedo, lambert, ny, share, sky);
    const double up = (0.5 + 0.5 * ny) * sky;  // the hemisphere's weight of the open sky
    const double want[3] = {albedo.x * (1.8 * lambert * share + (0.05 + (0.1 - 0.05) * up) + 0.03),
                            albedo.y * (1.6 * lambert * share + (0.04 + (0.15 - 0.04) * up) + 0.03),
                            albedo.z * (1.4 * lambert * share + (0.03 + (0.2 - 0.03) * up) + 0.03)};
    CHECK(got.x == Approx(want[0]).epsilon(1e-14));
    CHECK(got.y == Approx(want[1]).epsilon(1e-14));
    CHECK(got.z == Approx(want[2]).epsilon(1e-14));
  }
}

TEST_CASE("eachDrawnVertexGetsItsLambertTermAndTheOthersZero", "[gradient]") {
  TransformParams<float> t;
  const double sun[3] = {0.3, 0.8, -std::sqrt(1.0 - 0.09 - 0.64)};
  t.gouraud = 1;
  t.sun_x = float(sun[0]);
  t.sun_y = float(sun[1]);
  t.sun_z = float(sun[2]);
  test::TestRandom random(9);
  const std::size_t count = 777;
  std::vector<float> nx(count), ny(count), nz(count), lambert(count, -1.0f);
  std::vector<std::uint8_t> need(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double a = random.uniform(0, 2 * M_PI), b = random.uniform(-1, 1);
    const double r = std::sqrt(1 - b * b);
    nx[k] = float(r * std::cos(a));
    ny[k] = float(b);
    nz[k] = float(r * std::sin(a));
    need[k] = static_cast<std::uint8_t>(random.uniform(0, 4));
  }
  light_vertices<float>(t, IndexRange{3, count - 2}, nx, ny, nz, need, lambert);
  int lit = 0, dark = 0;
  for (std::size_t k = 0; k < count; ++k) {
    INFO("vertex " << k);
    if (k < 3 || k >= count - 2) {
      CHECK(lambert[k] == -1.0f);  // outside the range: untouched
      continue;
    }
    if (!(need[k] & kDraw)) {
      CHECK(lambert[k] == 0.0f);
      continue;
    }
    const double ndl = double(nx[k]) * double(t.sun_x) + double(ny[k]) * double(t.sun_y) +
                       double(nz[k]) * double(t.sun_z);
    CHECK(std::abs(double(lambert[k]) - std::max(0.0, ndl)) <= 3e-7);
    CHECK(lambert[k] >= 0.0f);
    lit += ndl > 0.01;
    dark += ndl < -0.01;
  }
  CHECK(lit > 50);
  CHECK(dark > 50);
}

TEST_CASE("theGradientFieldsAreReadAndBadOnesRefusedByName", "[gradient][scene]") {
  const Scene plain = resolve_scene("default", {});
  CHECK(plain.shading.mode == ShadingMode::kTextures);
  REQUIRE(plain.shading.gradient.stops.size() == 8);
  CHECK(!plain.shading.gradient.range);
  const Scene set = resolve_scene(
      "default", {"shading.mode=\"gradient\"", "shading.gradient.range=[-10, 500]",
                  "shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}, {\"at\": 1, "
                  "\"color\": [1, 0.5, 0.25]}]"});
  CHECK(set.shading.mode == ShadingMode::kGradient);
  REQUIRE(set.shading.gradient.range);
  CHECK((*set.shading.gradient.range)[1] == 500.0);
  REQUIRE(set.shading.gradient.stops.size() == 2);
  CHECK(set.shading.gradient.stops[1].color[2] == 0.25);
  // Printed and read back: the same scene.
  const Scene again = resolve_scene_text(scene_to_json(set).dump(), "again.json", ".", {});
  CHECK(scene_to_json(again) == scene_to_json(set));

  const auto refused = [](const std::string& override, const std::string& field,
                          const std::string& says) {
    INFO(override);
    CHECK_THROWS_WITH(resolve_scene("default", {override}),
                      Catch::Contains(field) && Catch::Contains(says));
  };
  refused("shading.mode=\"phong\"", "shading.mode", "gradient");
  refused("shading.gradient.range=[5, 5]", "shading.gradient.range", "low < high");
  refused("shading.gradient.range=[0, 1e9]", "shading.gradient.range", "out of range");
  refused("shading.gradient.range=[0]", "shading.gradient.range", "");
  refused("shading.gradient.stops=[]", "shading.gradient.stops", "2 to 16");
  refused("shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}]", "shading.gradient.stops",
          "2 to 16");
  refused("shading.gradient.stops={\"0\": {\"at\": 0.5}}", "shading.gradient.stops", "2 to 16");
  refused(
      "shading.gradient.stops=[{\"at\": 0.5, \"color\": [0, 0, 0]}, {\"at\": 0.25, "
      "\"color\": [0, 0, 0]}]",
      "shading.gradient.stops[1].at", "non-decreasing");
  refused("shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}, {\"color\": [0, 0, 0]}]",
          "shading.gradient.stops[1]", "`at` and `color`");
  refused(
      "shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}, {\"at\": 2, \"color\": "
      "[0, 0, 0]}]",
      "shading.gradient.stops[1].at", "out of range");
  refused(
      "shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}, {\"at\": 1, \"color\": "
      "[0, -1, 0]}]",
      "shading.gradient.stops[1].color", "out of range");
  refused(
      "shading.gradient.stops=[{\"at\": 0, \"color\": [0, 0, 0]}, {\"at\": 1, \"color\": "
      "[0, 0, 0], \"shade\": 1}]",
      "shading.gradient.stops[1].shade", "unknown key");
  std::string seventeen = "shading.gradient.stops=[";
  for (int k = 0; k < 17; ++k) {
    seventeen += std::string(k ? ", " : "") + "{\"at\": 0.5, \"color\": [0, 0, 0]}";
  }
  refused(seventeen + "]", "shading.gradient.stops", "2 to 16");
}

// The light of each covered pixel, with a white gradient, a white sun and no other light, is
// its Lambert term interpolated over its triangle: within the range of the three vertices'
// max(0, n . sun), computed here in double from the grid's normals. Per-pixel (renormalised)
// normals would leave that range where a triangle's normals diverge.
TEST_CASE("gradientPixelsAreLitByTheirTrianglesVertexLight", "[gradient][frame]") {
  const Scene scene = resolve_scene(
      "badlands",
      with(kGradientFrame,
           {"shading.mode=\"gradient\"",
            "shading.gradient.stops=[{\"at\": 0, \"color\": [1, 1, 1]}, {\"at\": 1, "
            "\"color\": [1, 1, 1]}]",
            "lighting.sun_color=[1, 1, 1]", "lighting.sun_intensity=1", "lighting.sky_intensity=0",
            "lighting.ambient=0", "lighting.exposure=1", "sky.fog_density=0",
            "terrain.water_level=null", "lighting.sun_elevation_deg=35"}));
  const SceneResources resources = load_scene_resources(scene);
  CHECK(resources.textures.empty());  // nothing synthesised for a gradient
  for (const Backend backend : {Backend::kReference, Backend::kSimd, Backend::kReferenceDouble}) {
    FrameRequest request;
    request.backend = backend;
    request.outputs.linear = request.outputs.primitive = request.outputs.normal = true;
    const Frame frame = render_frame(scene, resources, request);
    // The frame's own vertex normals: its precision's stages, which skip no drawn vertex's
    // inputs (tests/pipeline/skip_test.cc).
    const FramePlan plan = make_frame_plan(scene, resources.terrain_values());
    GridBuffers<float> float_grid(plan.layout);
    GridBuffers<double> double_grid(plan.layout);
    const bool in_double = backend == Backend::kReferenceDouble;
    if (in_double) {
      run_terrain_stages(plan, double_grid);
    } else {
      run_terrain_stages(plan, float_grid);
    }
    const auto normal = [&](std::uint32_t i, int c) -> double {
      if (in_double) {
        return c == 0 ? double_grid.nx[i] : (c == 1 ? double_grid.ny[i] : double_grid.nz[i]);
      }
      return c == 0 ? float_grid.nx[i] : (c == 1 ? float_grid.ny[i] : float_grid.nz[i]);
    };
    const double elevation = 35 * M_PI / 180, azimuth = scene.lighting.sun_azimuth_deg * M_PI / 180;
    const double sun[3] = {std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                           -std::cos(azimuth) * std::cos(elevation)};
    const raster::GridTriangles triangles{plan.layout,
                                          in_double ? double_grid.valid : float_grid.valid};
    std::size_t covered = 0, outside = 0, per_pixel_differs = 0;
    for (std::size_t k = 0; k < frame.image.primitive.size(); ++k) {
      if (frame.image.primitive[k] == raster::kNoPrimitive) {
        continue;
      }
      ++covered;
      std::uint32_t v[3];
      triangles.vertices(frame.image.primitive[k], v);
      double low = 1, high = 0;
      for (const std::uint32_t i : v) {
        const double ndl =
            std::max(0.0, normal(i, 0) * sun[0] + normal(i, 1) * sun[1] + normal(i, 2) * sun[2]);
        low = std::min(low, ndl);
        high = std::max(high, ndl);
      }
      const double light = frame.image.linear[3 * k];
      // The vertices' terms here in double, the frame's in its precision, the interpolation's
      // weights rounded: 1e-5 covers their difference.
      outside += light < low - 1e-5 || light > high + 1e-5;
      const float* n = &frame.image.normal[3 * k];
      const double phong = std::max(0.0, n[0] * sun[0] + n[1] * sun[1] + n[2] * sun[2]);
      per_pixel_differs += std::abs(phong - light) > 1e-3;
    }
    INFO("backend " << int(backend));
    CHECK(covered > frame.image.primitive.size() / 3);
    CHECK(outside == 0);
    CHECK(per_pixel_differs > covered / 50);  // Gouraud, not per-pixel light
  }
}

TEST_CASE("gradientFramesFetchNoTextureAndEqualTheUnfusedOracle", "[gradient][frame]") {
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{},
        {"lighting.shadows=true", "shading.gradient.range=[-20, 600]"}}) {
    const Scene textured = resolve_scene("default", with(kGradientFrame, extra));
    const Scene scene =
        resolve_scene("default", with(with(kGradientFrame, extra), {"shading.mode=\"gradient\""}));
    const SceneResources resources = load_scene_resources(scene);
    FrameRequest request;
    request.backend = Backend::kSimd;
    request.outputs.linear = true;
    const Frame frame = render_frame(scene, resources, request);
    const Frame with_textures = render_frame(textured, load_scene_resources(textured), request);
    INFO((extra.empty() ? "plain" : extra.front()));
    CHECK(test::frame_counter(frame, "pixels shaded as terrain") > 0);
    CHECK(test::frame_counter(frame, "texture fetches") == 0);
    CHECK(test::frame_counter(frame, "dither samples") == 0);
    CHECK(test::frame_counter(frame, "specular terms") == 0);
    CHECK(test::frame_counter(with_textures, "texture fetches") > 0);
    CHECK(frame.image.srgb != with_textures.image.srgb);
    const FrameImage whole = render_whole_frame(scene, resources);
    CHECK(frame.image.srgb == whole.srgb);
    CHECK(frame.image.linear == whole.linear);
  }
}

// The per-vertex Lambert term is counted in the render's memory estimate: one value a grid
// vertex in the frame's precision.
TEST_CASE("theRenderEstimateCountsTheVertexLight", "[gradient]") {
  const Scene textured = resolve_scene("default", kGradientFrame);
  const Scene gradient =
      resolve_scene("default", with(kGradientFrame, {"shading.mode=\"gradient\""}));
  const auto grid_bytes = [](const Scene& scene, Backend backend) {
    for (const auto& [part, size] : estimate_render_memory(scene, backend, {}).parts) {
      if (part.rfind("grid ", 0) == 0) {
        return size;
      }
    }
    FAIL("no grid in the estimate");
    return std::uintmax_t(0);
  };
  const std::uintmax_t vertices = std::uintmax_t(textured.grid.width) * textured.grid.height;
  CHECK(grid_bytes(gradient, Backend::kSimd) - grid_bytes(textured, Backend::kSimd) >=
        vertices * sizeof(float));
  CHECK(grid_bytes(gradient, Backend::kReferenceDouble) -
            grid_bytes(textured, Backend::kReferenceDouble) >=
        vertices * sizeof(double));
}

}  // namespace
}  // namespace relief
