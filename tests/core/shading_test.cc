// Stage 8: layer weights, proto-texture mip chains and sampling, GL's LOD formula, water.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/layer_weights.h"
#include "core/proto_texture.h"
#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "core/stage_params.h"
#include "core/texture_synthesis.h"
#include "core/water.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"
#include "raster/resolve.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

struct PlanFixture {
  Scene scene;
  NoiseLattice lattice;
  std::optional<HeightSketch> sketch;  // terrain.sketch's texels, where the scene has one
  FramePlan frame;
  std::vector<ProtoTexture> textures;
  ShadingPlan plan;
  ShadeParams<double> params;  // the plan rounded to double: its values unchanged

  explicit PlanFixture(Scene s)
      : scene(std::move(s)),
        lattice(make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size)),
        sketch(load_height_sketch(scene)),
        frame(make_frame_plan(scene, lattice, sketch ? &*sketch : nullptr)) {
    for (const MaterialLayer& layer : scene.shading.layers) {
      (void)layer;
      RgbImage flat{4, std::vector<float>(48, 0.5f)};
      textures.push_back(build_proto_texture(flat, 0.0));
    }
    plan = make_shading_plan(scene, frame, lattice.size);
    params = make_shade_params<double>(plan);
  }
};

std::size_t layer_index(const Scene& scene, const std::string& name) {
  for (std::size_t k = 0; k < scene.shading.layers.size(); ++k) {
    if (scene.shading.layers[k].name == name) {
      return k;
    }
  }
  FAIL("no layer " << name);
  return 0;
}

double degrees_to_slope(double deg) {
  return std::tan(deg * M_PI / 180.0);
}

TEST_CASE("layerWeightsSumToOneEverywhereForEveryPreset", "[shading]") {
  for (const std::string& preset : preset_names()) {
    const PlanFixture f(resolve_scene(preset, {}));
    test::TestRandom random(5);
    for (int k = 0; k < 20000; ++k) {
      double w[limits::kMaxMaterialLayers];
      layer_weights(f.params, random.uniform(-2000, 3000), random.uniform(0, 6),
                    random.uniform(-2, 2), w);
      double sum = 0;
      for (std::size_t l = 0; l < f.plan.layers.size(); ++l) {
        REQUIRE(w[l] >= 0.0);
        sum += w[l];
      }
      INFO(preset);
      REQUIRE(sum == Approx(1.0).epsilon(1e-12));
    }
  }
}

TEST_CASE("grassVanishesOnSlopesAboveTheRockThreshold", "[shading]") {
  const Scene scene = resolve_scene("alpine", {});
  const std::size_t grass = layer_index(scene, "grass"), rock = layer_index(scene, "rock");
  const MaterialLayer& g = scene.shading.layers[grass];
  // Without dithering the grass ramp ends at its upper slope plus the spread.
  const PlanFixture f(scene);
  const double beyond = degrees_to_slope(g.slope_deg[1] + g.slope_spread_deg + 0.01);
  for (double height = 10; height < 500; height += 7) {
    double w[limits::kMaxMaterialLayers];
    layer_weights(f.params, height - scene.camera.position[1], beyond, 0.0, w);
    CHECK(w[grass] < 1e-12);
    CHECK(w[rock] > 0.5);
  }
  // With dithering the ramp moves by at most amount / 2 * max|noise| of its width.
  const double shift =
      0.5 * scene.shading.dither * std::max(-f.lattice.min_value, f.lattice.max_value);
  const double start = degrees_to_slope(g.slope_deg[1] - g.slope_spread_deg);
  const double end = degrees_to_slope(g.slope_deg[1] + g.slope_spread_deg);
  const double dithered_end = end + shift * (end - start);
  for (double noise : {-4.0, -1.0, 0.0, 2.0, 4.0}) {
    double w[limits::kMaxMaterialLayers];
    layer_weights(f.params, 200.0 - scene.camera.position[1], dithered_end * 1.001,
                  0.5 * scene.shading.dither * noise, w);
    CHECK(w[grass] < 1e-12);
  }
}

TEST_CASE("layerHeightRangesAreRespected", "[shading]") {
  const Scene scene = resolve_scene("alpine", {});
  const PlanFixture f(scene);
  const std::size_t snow = layer_index(scene, "snow"), bed = layer_index(scene, "bed");
  const MaterialLayer& s = scene.shading.layers[snow];
  const MaterialLayer& b = scene.shading.layers[bed];
  const double water = *scene.terrain.water_level;
  const double camera_y = scene.camera.position[1];  // the pixels' heights are camera-relative
  for (double slope : {0.0, 0.2, 0.5}) {
    double w[limits::kMaxMaterialLayers];
    layer_weights(f.params, s.height[0] - s.height_spread - 1.0 - camera_y, slope, 0.0, w);
    CHECK(w[snow] == 0.0);
    layer_weights(f.params, s.height[0] + s.height_spread + 1.0 - camera_y, slope, 0.0, w);
    CHECK(w[snow] > 0.5);
    // The bed's range is measured from the water level.
    layer_weights(f.params, water + b.height[1] + b.height_spread + 0.5 - camera_y, slope, 0.0, w);
    CHECK(w[bed] == 0.0);
    layer_weights(f.params, water - 20.0 - camera_y, slope, 0.0, w);
    CHECK(w[bed] == Approx(1.0));
  }
}

double channel_variance(const float* rgb, int size, int c) {
  double sum = 0, sum_sq = 0;
  const double n = double(size) * size;
  for (std::size_t k = c; k < 3 * std::size_t(size) * size; k += 3) {
    sum += rgb[k];
    sum_sq += double(rgb[k]) * rgb[k];
  }
  return sum_sq / n - (sum / n) * (sum / n);
}

TEST_CASE("mipChainPreservesTheMeanAndLosesVarianceLevelByLevel", "[shading]") {
  const RgbImage rock = synthesize_texture("rock", 128);
  std::vector<std::vector<double>> variance_by_blend;
  for (double blend : {0.0, 0.2, 0.5}) {
    const ProtoTexture t = build_proto_texture(rock, blend);
    REQUIRE(t.levels.size() == 8);  // 128, 64, ..., 1
    std::vector<double> variances;
    for (std::size_t l = 0; l < t.levels.size(); ++l) {
      const MipLevel& level = t.levels[l];
      const float* rgb = t.level_texels(int(l));
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (std::size_t k = c; k < 3 * std::size_t(level.size) * level.size; k += 3) {
          sum += rgb[k];
        }
        CHECK(sum / (double(level.size) * level.size) == Approx(t.mean[c]).epsilon(1e-5));
      }
      variances.push_back(channel_variance(rgb, level.size, 0) +
                          channel_variance(rgb, level.size, 1) +
                          channel_variance(rgb, level.size, 2));
    }
    for (std::size_t l = 1; l + 1 < variances.size(); ++l) {
      CHECK(variances[l] < variances[l - 1]);  // strictly falling (the last level is 1 x 1)
    }
    variance_by_blend.push_back(variances);
  }
  // A larger blend toward the mean removes variance faster, from level 1 on.
  for (std::size_t l = 1; l + 1 < variance_by_blend[0].size(); ++l) {
    CHECK(variance_by_blend[1][l] < variance_by_blend[0][l]);
    CHECK(variance_by_blend[2][l] < variance_by_blend[1][l]);
  }
}

TEST_CASE("textureLodFollowsGlsFormula", "[shading]") {
  // lambda = log2(max(|(du/dx, dv/dx)|, |(du/dy, dv/dy)|) * size), u in repeats.
  struct Case {
    float dudx, dvdx, dudy, dvdy;
  };
  for (const Case c : {Case{1.0f / 256, 0, 0, 1.0f / 256}, Case{0.01f, 0.02f, -0.003f, 0.001f},
                       Case{0, 0.5f, 0.25f, 0}, Case{1e-6f, 0, 0, 1e-6f}}) {
    const double rho = std::max(std::hypot(c.dudx * 256.0, c.dvdx * 256.0),
                                std::hypot(c.dudy * 256.0, c.dvdy * 256.0));
    CHECK(texture_lod(256, c.dudx, c.dvdx, c.dudy, c.dvdy) == Approx(std::log2(rho)).margin(1e-5));
  }
  CHECK(texture_lod(256, 0, 0, 0, 0) == kMagnificationLod);
}

TEST_CASE("textureLodOnATiltedPlaneEqualsGlsFormulaFromTheGeometry", "[shading]") {
  // A ground plane 10 units below a camera pitched 30 degrees down, texture coordinates
  // u = x / 4, v = z / 4. The LOD from the resolve's quad derivatives must equal GL's formula
  // applied to the same differences of the exact (ray/plane) mapping.
  const double f = 1.0 / std::tan(M_PI / 6), pitch = -M_PI / 6, height = 10;
  const glm::dvec3 forward(0, std::sin(pitch), -std::cos(pitch)), right(1, 0, 0);
  const glm::dvec3 up = glm::cross(right, forward);
  std::vector<float> x, y, z, w, u, v;
  for (const auto& p : {glm::dvec3(-60, -height, 2), glm::dvec3(60, -height, 2),
                        glm::dvec3(60, -height, -200), glm::dvec3(-60, -height, -200)}) {
    x.push_back(float(glm::dot(p, right) * f));
    y.push_back(float(glm::dot(p, up) * f));
    z.push_back(0.1f);
    w.push_back(float(glm::dot(p, forward)));
    u.push_back(float(p.x / 4));
    v.push_back(float(p.z / 4));
  }
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  raster::RasterState state;
  state.width = state.height = 64;
  state.viewport = {0, 0, 64, 64};
  const raster::ClipVertices clip{x, y, z, w};
  raster::VisibilityBuffer b;
  raster::rasterize(state, clip, raster::IndexedTriangles{indices}, b);
  const std::span<const float> streams[2] = {u, v};
  raster::ResolvedFrame r;
  raster::resolve(b, raster::VertexPositions::from_clip(clip, state.viewport),
                  raster::IndexedTriangles{indices},
                  std::span<const std::span<const float>>(streams), 2, r);
  auto uv = [&](double px, double py) {  // exact texture coordinates at window point (px, py)
    const glm::dvec3 ray = forward + ((2 * px / 64 - 1) / f) * right + ((2 * py / 64 - 1) / f) * up;
    const glm::dvec3 hit = ray * (-height / ray.y);
    return glm::dvec2(hit.x / 4, hit.z / 4);
  };
  int checked = 0;
  for (int py = 0; py < 64; ++py) {
    for (int px = 0; px < 64; ++px) {
      const std::size_t k = b.index(px, py);
      if (b.primitive[k] == raster::kNoPrimitive) {
        continue;
      }
      const double left = (px & 1) ? px - 0.5 : px + 0.5, bottom = (py & 1) ? py - 0.5 : py + 0.5;
      const glm::dvec2 ddx = uv(left + 1, py + 0.5) - uv(left, py + 0.5);
      const glm::dvec2 ddy = uv(px + 0.5, bottom + 1) - uv(px + 0.5, bottom);
      const double expected = std::log2(std::max(glm::length(ddx), glm::length(ddy)) * 256.0);
      const float lod = texture_lod(256, r.ddx[0][k], r.ddx[1][k], r.ddy[0][k], r.ddy[1][k]);
      REQUIRE(lod == Approx(expected).margin(2e-3));
      ++checked;
    }
  }
  CHECK(checked > 1000);
}

TEST_CASE("theNearestMipLevelIsGlsLinearMipmapNearestAndFetchesOneLevel", "[shading]") {
  // GL 4.5 §8.14.3: level 0 for lambda <= 1/2, else ceil(lambda + 1/2) - 1.
  CHECK(nearest_mip_lod(-64.0f) == 0.0f);
  CHECK(nearest_mip_lod(0.5f) == 0.0f);
  CHECK(nearest_mip_lod(std::nextafter(0.5f, 1.0f)) == 1.0f);
  CHECK(nearest_mip_lod(1.5f) == 1.0f);
  CHECK(nearest_mip_lod(1.50001f) == 2.0f);
  CHECK(nearest_mip_lod(2.49f) == 2.0f);
  CHECK(nearest_mip_lod(std::nanf("")) == 0.0f);
  const ProtoTexture t = build_proto_texture(synthesize_texture("rock", 64), 0.3);
  const int last = static_cast<int>(t.levels.size()) - 1;
  // A whole lod is its level alone: the texel of that level at its centres.
  for (int level = 1; level < last && t.levels[level].size >= 4; ++level) {
    const int n = t.levels[level].size;
    const float u = 1.5f / float(n), v = 2.5f / float(n);
    const Rgb got = sample_trilinear(t, u, v, nearest_mip_lod(float(level) + 0.3f));
    const float* texel = t.level_texels(level) + 3 * (2 * n + 1);
    for (int c = 0; c < 3; ++c) {
      CHECK(got[c] == texel[c]);
    }
  }
  // The filter changes the image and the scene file reads it back.
  const Scene bilinear = resolve_scene("default", {"shading.texture_filter=\"bilinear\""});
  CHECK(bilinear.shading.texture_filter == TextureFilter::kBilinear);
  CHECK_THROWS(resolve_scene("default", {"shading.texture_filter=\"anisotropic\""}));
}

TEST_CASE("trilinearSamplingHitsTexelsRepeatsAndBlendsLevels", "[shading]") {
  const ProtoTexture t = build_proto_texture(synthesize_texture("grass", 64), 0.3);
  const float* level0 = t.level_texels(0);
  const float* level1 = t.level_texels(1);
  for (int j : {0, 7, 63}) {
    for (int i : {0, 31, 63}) {
      const float u = (i + 0.5f) / 64, v = (j + 0.5f) / 64;
      const Rgb a = sample_trilinear(t, u, v, 0.0f);
      const Rgb b = sample_trilinear(t, u + 3.0f, v - 2.0f, -5.0f);  // repeat; magnification
      for (int c = 0; c < 3; ++c) {
        CHECK(a[c] == level0[3 * (j * 64 + i) + c]);
        CHECK(b[c] == Approx(a[c]).margin(1e-6));
      }
    }
  }
  // Half way between levels 0 and 1 at a texel centre of level 1: the mean of the two.
  const float u = 0.5f / 32, v = 0.5f / 32;
  const Rgb mid = sample_trilinear(t, u, v, 0.5f);
  const Rgb l0 = sample_trilinear(t, u, v, 0.0f), l1 = sample_trilinear(t, u, v, 1.0f);
  for (int c = 0; c < 3; ++c) {
    CHECK(l1[c] == level1[c]);
    CHECK(mid[c] == Approx(0.5 * (l0[c] + l1[c])).margin(1e-6));
  }
}

TEST_CASE("textureCoordinatesWrapWithoutOverflowFarAwayAndForTinyTiles", "[shading]") {
  // Far from the camera or with tiny tiles u * size exceeds 2^31 (UBSan saw 3e9 converted to
  // int). The sampler wraps before converting; here the texel it must fetch is worked out
  // independently, in double and 64-bit integers, from the same float s = u * 64 - 0.5.
  const ProtoTexture t = build_proto_texture(synthesize_texture("rock", 64), 0.3);
  const float* level0 = t.level_texels(0);
  const float v = 0.5f / 64;  // a texel centre of row 0: no blending in v
  for (float u : {3e9f, -3e9f, 2147483648.0f, 1.5e10f, -7.77e12f, 1e30f, -3.4e38f, 0x1.fffffep127f,
                  33554431.75f, -16777217.0f, 1234567.125f}) {
    float s = u * 64.0f - 0.5f;
    s = std::isfinite(s) ? s : 0.0f;  // u * 64 overflows float: the sampler fetches texel 0
    const double floor_s = std::floor(double(s));
    const double a = double(s) - floor_s;
    const auto i0 = static_cast<std::int64_t>(std::fmod(floor_s, 64.0) + 64.0) % 64;
    const std::int64_t i1 = (i0 + 1) % 64;
    const Rgb sample = sample_trilinear(t, u, v, 0.0f);
    for (int c = 0; c < 3; ++c) {
      const double expected = level0[3 * i0 + c] + a * (level0[3 * i1 + c] - level0[3 * i0 + c]);
      INFO("u = " << u << ", channel " << c);
      CHECK(sample[c] == Approx(expected).margin(1e-6));
    }
  }
  // Non-finite coordinates (never produced by stage 7) sample texel 0 rather than convert NaN.
  const Rgb nan_sample = sample_trilinear(t, std::nanf(""), v, 0.0f);
  CHECK(nan_sample[0] == level0[0]);
}

TEST_CASE("srgbBytesAreTheRoundedTransferFunction", "[shading]") {
  test::TestRandom random(9);
  for (int k = 0; k < 200000; ++k) {
    const float x = float(std::pow(random.uniform(0, 1), 3.0));
    const double reference = 255.0 * srgb_encode(x);
    // Away from exact ties the code is round(255 encode(x)).
    if (std::abs(reference - std::floor(reference) - 0.5) > 1e-6) {
      REQUIRE(srgb_byte(x) == std::lround(reference));
    }
  }
  CHECK(srgb_byte(-1.0f) == 0);
  CHECK(srgb_byte(std::nanf("")) == 0);
  CHECK(srgb_byte(1.0f) == 255);
  CHECK(srgb_byte(7.0f) == 255);
}

TEST_CASE("waterFadesIntoTheGroundAtTheShorelineAndDeepensWithDepth", "[shading]") {
  const PlanFixture f(resolve_scene("lake", {}));
  const Vec3<double> view = normalize_or(Vec3<double>{0.3, -0.4, -1.0}, Vec3<double>{0, -1, 0});
  const Vec3<double> ground{0.3, 0.25, 0.2};
  ShadeWork work;
  // At zero depth only a weak Fresnel reflection covers the ground.
  const Vec3<double> shore =
      shade_water(f.params, f.lattice, nullptr, view, 100.0, 0.0, ground, 1e3, 1.0, {}, 0.0, work);
  CHECK(std::abs(shore.x - ground.x) < 0.05);
  CHECK(std::abs(shore.y - ground.y) < 0.05);
  // Deeper water hides the ground: the result stops depending on it.
  const Vec3<double> deep_a = shade_water(f.params, f.lattice, nullptr, view, 100.0, 200.0, ground,
                                          1e3, 1.0, {}, 0.0, work);
  const Vec3<double> deep_b = shade_water(f.params, f.lattice, nullptr, view, 100.0, 200.0,
                                          Vec3<double>{0, 0, 0}, 1e3, 1.0, {}, 0.0, work);
  CHECK(std::abs(deep_a.x - deep_b.x) < 1e-6);
  // Red is absorbed first: deep water is greener than it is red.
  CHECK(deep_a.y > deep_a.x);
  // Continuous in depth.
  double previous =
      shade_water(f.params, f.lattice, nullptr, view, 100.0, 0.0, ground, 1e3, 1.0, {}, 0.0, work)
          .x;
  for (double depth = 0.01; depth < 30; depth += 0.01) {
    const double now = shade_water(f.params, f.lattice, nullptr, view, 100.0, depth, ground, 1e3,
                                   1.0, {}, 0.0, work)
                           .x;
    REQUIRE(std::abs(now - previous) < 0.01);
    previous = now;
  }
}

}  // namespace
}  // namespace relief
