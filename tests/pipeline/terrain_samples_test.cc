// The terrain on a regular grid (pipeline/terrain_samples.h), for relief export: each sample
// where it should be (texel centres of the region) with the octaves its spacing carries, against
// the terrain evaluated from a plan centred elsewhere and the test's own §4.1 octave count; a
// height field's samples against the test's own cubic B-spline; central-difference normals of a
// plane exact; the layer bytes summing to 255; and the samples the same for any thread count.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <tbb/task_arena.h>
#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "pipeline/scene_resources.h"
#include "pipeline/terrain_samples.h"
#include "tests/support/bspline_oracle.h"
#include "tests/support/cli_support.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

double x_of(const SampleRegion& r, int i) {
  return r.rect[0] + (i + 0.5) * (r.rect[2] - r.rect[0]) / r.width;
}
double z_of(const SampleRegion& r, int j) {
  return r.rect[1] + (j + 0.5) * (r.rect[3] - r.rect[1]) / r.height;
}

TEST_CASE("proceduralSamplesAreTheTerrainAtTheirPointsWithTheirSpacingsOctaves", "[pipeline]") {
  Scene scene = test::small_scene();
  const SceneResources resources = load_scene_resources(scene);
  SampleRegion region{{1234.5, -800.25, 1834.5, -500.25}, 37, 19};  // cells 16.2 x 15.8
  const TerrainSamples samples = sample_terrain(scene, resources, region, {});
  REQUIRE(samples.heights.size() == 37u * 19u);
  // §4.1's count for spacing sigma (the amplitude criterion of the default scene): the finest
  // octave kappa with amplitude r^(-kappa H) = sigma, nu = kappa - k0 + 1 octaves, in [1, N].
  const TerrainSettings& t = scene.terrain;
  REQUIRE(t.lod.criterion == LodCriterion::kAmplitude);
  const double sigma = std::max(600.0 / 37, 300.0 / 19);
  const double kappa = (std::log2(t.amplitude) - std::log2(sigma)) / (t.H * std::log2(t.r));
  const double nu = std::clamp(kappa + t.lod.bias - t.first_octave + 1, 1.0,
                               double(t.last_octave - t.first_octave + 1));
  // The terrain from a plan centred at the scene's camera, far from the region's centre.
  const FramePlan plan = make_frame_plan(scene, resources.terrain_values());
  const auto& c = scene.camera.position;
  double worst = 0;
  for (int j = 0; j < region.height; ++j) {
    for (int i = 0; i < region.width; ++i) {
      const double expected =
          fbm_height<double>(plan.terrain, x_of(region, i) - c[0], z_of(region, j) - c[2], nu) +
          c[1];
      worst = std::max(worst, std::abs(samples.heights[std::size_t(j) * 37 + i] - expected));
    }
  }
  CHECK(worst < 1e-3);  // float heights of a few hundred units: a few ulps
  CHECK(samples.low == *std::min_element(samples.heights.begin(), samples.heights.end()));
  CHECK(samples.high == *std::max_element(samples.heights.begin(), samples.heights.end()));
}

TEST_CASE("heightFieldSamplesAreItsBSplineInsideAndBeyondItsExtent", "[pipeline]") {
  test::TempDir dir("samples");
  const int w = 21, h = 13;
  const std::vector<float> unit = test::random_unit_samples(std::size_t(w) * h, 11);
  const std::string file = test::write_file(dir.path() / "f.pfm", test::pfm_bytes(w, h, unit));
  Scene scene = test::small_scene();
  HeightFieldSettings field;
  field.image = file;
  field.extent = {-1000.0, 200.0, 1100.0, 1500.0};
  field.height = {-50.0, 450.0};
  scene.terrain.heightfield = field;
  scene.terrain.base_height = 0.0;
  const SceneResources resources = load_scene_resources(scene);
  std::vector<double> heights(unit.size());
  for (std::size_t k = 0; k < unit.size(); ++k) {
    heights[k] = double(float(-50.0 + 500.0 * double(unit[k])));  // the field's floats
  }
  const SampleRegion region{{-1300.0, 0.0, 900.0, 1700.0}, 29, 23};  // over an edge
  const TerrainSamples samples = sample_terrain(scene, resources, region, {});
  for (int j = 0; j < region.height; ++j) {
    for (int i = 0; i < region.width; ++i) {
      const double s = (x_of(region, i) + 1000.0) * w / 2100.0 - 0.5;
      const double t = (z_of(region, j) - 200.0) * h / 1300.0 - 0.5;
      CHECK(samples.heights[std::size_t(j) * region.width + i] ==
            Approx(test::bspline_at(heights.data(), w, h, s, t)).margin(1e-3));
    }
  }
}

TEST_CASE("normalsOfAPlaneAreExactAndLayerBytesSumTo255", "[pipeline]") {
  test::TempDir dir("samples");
  const int w = 40, h = 40;
  std::vector<float> unit(std::size_t(w) * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      unit[std::size_t(j) * w + i] = float(i) / 64.0f + float(j) / 128.0f;  // exact floats
    }
  }
  Scene scene = test::small_scene();
  HeightFieldSettings field;
  field.image = test::write_file(dir.path() / "ramp.pfm", test::pfm_bytes(w, h, unit));
  field.extent = {0.0, 0.0, 4000.0, 4000.0};  // 100 units a texel
  field.height = {0.0, 6400.0};               // 1 unit up per texel along x, 0.5 along z
  scene.terrain.heightfield = field;
  const SceneResources resources = load_scene_resources(scene);
  // Well inside: the B-spline reproduces a linear ramp exactly there.
  const SampleRegion region{{1000.0, 1000.0, 3000.0, 3000.0}, 17, 17};
  const TerrainSamples samples = sample_terrain(scene, resources, region, {true, true});
  const double gx = 1.0, gz = 0.5, norm = std::sqrt(gx * gx + 1 + gz * gz);
  for (std::size_t k = 0; k < samples.heights.size(); ++k) {
    CHECK(samples.normals[3 * k] == Approx(-gx / norm).margin(1e-6));
    CHECK(samples.normals[3 * k + 1] == Approx(1 / norm).margin(1e-6));
    CHECK(samples.normals[3 * k + 2] == Approx(-gz / norm).margin(1e-6));
    int sum = 0;
    for (int l = 0; l < samples.layers; ++l) {
      sum += samples.weights[std::size_t(samples.layers) * k + l];
    }
    CHECK(sum == 255);
  }
}

TEST_CASE("samplesAreTheSameForAnyThreadCount", "[pipeline]") {
  Scene scene = test::small_scene();
  scene.terrain.warp.enabled = true;
  const SceneResources resources = load_scene_resources(scene);
  const SampleRegion region{{-3000.0, -3000.0, 3000.0, 1000.0}, 70, 131};  // several bands
  const auto sample = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return sample_terrain(scene, resources, region, {true, true}); });
  };
  const TerrainSamples one = sample(1), two = sample(2);
  CHECK(one.heights == two.heights);
  CHECK(one.normals == two.normals);
  CHECK(one.weights == two.weights);
}

}  // namespace
}  // namespace relief
