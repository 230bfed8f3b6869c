// §3 Eq. 2's basis images (core/basis_images.h, core/periodic_gaussian.h): the composition,
// the filters, the seam measure. The scene field and the image files:
// tests/cli/basis_input_test.cc; whole frames: tests/pipeline/basis_frame_test.cc.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <stb_image_write.h>
#include <catch2/catch.hpp>

#include "core/basis_images.h"
#include "core/interpolant.h"
#include "core/periodic_gaussian.h"
#include "core/scene/scene_json.h"
#include "pipeline/basis_resources.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

GreyGrid random_grid(int side, unsigned seed) {
  test::TestRandom random(seed);
  GreyGrid g;
  g.side = side;
  g.values.resize(std::size_t(side) * std::size_t(side));
  for (double& v : g.values) {
    v = random.uniform(0.0, 1.0);
  }
  return g;
}

double mean_of(const GreyGrid& g) {
  double sum = 0.0;
  for (double v : g.values) {
    sum += v;
  }
  return sum / double(g.values.size());
}

double variance_of(const GreyGrid& g) {
  const double mean = mean_of(g);
  double sum = 0.0;
  for (double v : g.values) {
    sum += (v - mean) * (v - mean);
  }
  return sum / double(g.values.size());
}

// g shifted by (sx, sy) periodically: out(x, y) = g(x - sx, y - sy).
GreyGrid shifted(const GreyGrid& g, int sx, int sy) {
  GreyGrid out = g;
  const int n = g.side;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      out.values[std::size_t(y) * n + x] = g.at((x - sx + n) % n, (y - sy + n) % n);
    }
  }
  return out;
}

GreyGrid ramp(int side) {
  GreyGrid g;
  g.side = side;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      g.values.push_back(double(x) / (side - 1));
    }
  }
  return g;
}

// Float rounding of a value of magnitude up to `scale`.
constexpr double kFloatStep = 0x1.0p-24;

TEST_CASE("constantWeightsGiveTheConvexCombinationRenormalised", "[basis]") {
  const GreyGrid a = random_grid(16, 1), b = random_grid(16, 2);
  const std::vector<BasisTerm> tenths = {{&a, nullptr, 0.3}, {&b, nullptr, 0.7}};
  const std::vector<BasisTerm> sevenths = {{&a, nullptr, 3.0}, {&b, nullptr, 7.0}};
  const NoiseLattice s = compose_basis(tenths, 16);
  const NoiseLattice t = compose_basis(sevenths, 16);
  REQUIRE(s.size == 16);
  CHECK(s.mask == 15);
  for (std::size_t k = 0; k < s.values.size(); ++k) {
    const double exact = 0.3 * a.values[k] + 0.7 * b.values[k];
    CHECK(std::abs(s.values[k] - exact) <= kFloatStep);
    CHECK(std::abs(t.values[k] - exact) <= kFloatStep);  // 0.3 / 0.7 is 3 / 7
  }
  CHECK(s.min_value == *std::min_element(s.values.begin(), s.values.end()));
  CHECK(s.max_value == *std::max_element(s.values.begin(), s.values.end()));
}

TEST_CASE("weightImagesWeighEveryTexelOnItsOwn", "[basis]") {
  const GreyGrid a = random_grid(8, 3), b = random_grid(8, 4), w = random_grid(8, 5);
  const std::vector<BasisTerm> terms = {{&a, &w, 0.0}, {&b, nullptr, 0.5}};
  const NoiseLattice s = compose_basis(terms, 8);
  for (std::size_t k = 0; k < s.values.size(); ++k) {
    const double exact = (w.values[k] * a.values[k] + 0.5 * b.values[k]) / (w.values[k] + 0.5);
    CHECK(std::abs(s.values[k] - exact) <= kFloatStep);
  }
  // Where the weights sum to zero the combination is undefined: refused, naming the texel of
  // the image as the user drew it (the same one when the grid is mirrored).
  GreyGrid zero = w;
  zero.values[3 * 8 + 2] = 0.0;  // texel (2, 3)
  const std::vector<BasisTerm> alone = {{&a, &zero, 0.0}};
  CHECK_THROWS_WITH(compose_basis(alone, 8), Catch::Contains("sum to 0 at texel (2, 3)"));
  const GreyGrid big_a = mirror_grid(a), big_zero = mirror_grid(zero);
  const std::vector<BasisTerm> mirrored = {{&big_a, &big_zero, 0.0}};
  CHECK_THROWS_WITH(compose_basis(mirrored, 8), Catch::Contains("sum to 0 at texel (2, 3)"));
}

TEST_CASE("mirroringRepeatsTheImageReflectedAndTheSeamMeasureSeesTiling", "[basis]") {
  const GreyGrid r = ramp(64);
  CHECK(seam_measure(r) == Approx(63.0).epsilon(1e-12));  // W - 1 for a ramp
  const GreyGrid m = mirror_grid(r);
  REQUIRE(m.side == 128);
  CHECK(m.at(127, 9) == r.at(0, 9));
  CHECK(m.at(64, 100) == r.at(63, 27));
  CHECK(seam_measure(m) <= 1.0);
  // An image built periodic, a smoothed random grid, tiles: its measure is about 1.
  GreyGrid smooth = random_grid(64, 6);
  periodic_gaussian_blur(smooth.values, 64, 3.0);
  CHECK(seam_measure(smooth) == Approx(1.0).margin(0.3));
  // So do the shipped basis images.
  for (const char* name : {"craters", "dunes", "ridges"}) {
    Scene scene;
    scene.terrain.basis = BasisSettings{};
    BasisImageSettings image;
    image.image = std::string("builtin:basis/") + name;
    scene.terrain.basis->images.push_back(image);
    const std::vector<double> measures = basis_seam_measures(scene);
    REQUIRE(measures.size() == 1);
    INFO(name << " seam measure " << measures[0]);
    CHECK(measures[0] == Approx(1.0).margin(0.5));
  }
}

TEST_CASE("theLowPassIsTheGaussianAndKeepsTheMean", "[basis]") {
  // A unit impulse blurred: the Gaussian of sigma texels (its periodic copies are below 1e-30
  // at this size).
  const int n = 64;
  const double sigma = 2.5;
  std::vector<double> impulse(n * n, 0.0);
  impulse[0] = 1.0;
  periodic_gaussian_blur(impulse, n, sigma);
  double largest_error = 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int dx = std::min(x, n - x), dy = std::min(y, n - y);
      const double g = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma)) /
                       (2 * std::numbers::pi * sigma * sigma);
      largest_error = std::max(largest_error, std::abs(impulse[std::size_t(y) * n + x] - g));
    }
  }
  CHECK(largest_error < 1e-12);
  // On a random image: the mean kept, the variance reduced; periodic: a shifted image gives
  // the shifted result.
  const GreyGrid image = random_grid(n, 7);
  BasisImageSettings low;
  low.low_pass = 1.5;
  GreyGrid blurred = image, moved = shifted(image, 5, 61);
  filter_basis_image(blurred, low, "f");
  filter_basis_image(moved, low, "f");
  CHECK(mean_of(blurred) == Approx(mean_of(image)).margin(1e-12));
  CHECK(variance_of(blurred) < 0.2 * variance_of(image));
  const GreyGrid expected = shifted(blurred, 5, 61);
  for (std::size_t k = 0; k < moved.values.size(); ++k) {
    CHECK(std::abs(moved.values[k] - expected.values[k]) < 1e-12);
  }
}

TEST_CASE("theHighPassHasMeanZeroAndNormalizeGivesUnitVariance", "[basis]") {
  const GreyGrid image = random_grid(32, 8);
  BasisImageSettings high;
  high.high_pass = 4.0;
  GreyGrid detail = image;
  filter_basis_image(detail, high, "f");
  CHECK(std::abs(mean_of(detail)) < 1e-12);
  CHECK(variance_of(detail) > 0.0);
  BasisImageSettings all;
  all.low_pass = 0.7;
  all.high_pass = 6.0;
  all.normalize = true;
  GreyGrid normal = image;
  filter_basis_image(normal, all, "f");
  CHECK(std::abs(mean_of(normal)) < 1e-12);
  CHECK(variance_of(normal) == Approx(1.0).epsilon(1e-12));
  // A constant image has no variance to normalise: refused, naming the field.
  GreyGrid flat = image;
  std::fill(flat.values.begin(), flat.values.end(), 0.25);
  BasisImageSettings only_normalize;
  only_normalize.normalize = true;
  CHECK_THROWS_WITH(filter_basis_image(flat, only_normalize, "terrain.basis.images[2].image"),
                    Catch::Contains("terrain.basis.images[2].image cannot be normalized: its "
                                    "variance is 0"));
}

TEST_CASE("oneImageOfWeightOneIsTheAuxiliaryFunctionItself", "[basis]") {
  test::TempDir dir("basis");
  const int n = 32;
  std::vector<unsigned char> grey(n * n);
  for (int k = 0; k < n * n; ++k) {
    grey[std::size_t(k)] = static_cast<unsigned char>((k * 37 + k / n * 11) % 256);
  }
  const std::string file = (dir.path() / "one.png").string();
  REQUIRE(stbi_write_png(file.c_str(), n, n, 1, grey.data(), n) != 0);
  Scene scene;
  scene.terrain.basis = BasisSettings{};
  BasisImageSettings image;
  image.image = file;
  scene.terrain.basis->images.push_back(image);
  const std::optional<NoiseLattice> s = load_basis_grid(scene);
  REQUIRE(s);
  REQUIRE(s->size == n);
  for (std::size_t k = 0; k < grey.size(); ++k) {
    CHECK(s->values[k] == float(grey[k] / 255.0));
  }
  // Stage 3 runs with its side as the period and tile_size / side as the cell.
  const TerrainSettings t = stage3_terrain(scene.terrain, s->size);
  CHECK(t.lattice_size == n);
  CHECK(t.horizontal_scale == scene.terrain.basis->tile_size / n);
  CHECK(stage3_terrain(Scene{}.terrain, 99).horizontal_scale == Scene{}.terrain.horizontal_scale);
}

}  // namespace
}  // namespace relief

namespace relief {
namespace {

// The B-spline refinement of the composed grid (terrain.basis.upsample): a convex combination
// that keeps constants, reproduces the spline's (1, 4, 1) / 6 at the coarse texels, stays
// periodic, and removes the terraces a smooth image gets from stage 3's interpolants.
TEST_CASE("theBsplineRefinementIsPeriodicConvexAndRemovesTheTerraces", "[basis]") {
  const GreyGrid coarse = random_grid(16, 7);
  for (const int factor : {1, 2, 4, 8}) {
    INFO("factor " << factor);
    const GreyGrid fine = bspline_refine(coarse, factor);
    REQUIRE(fine.side == 16 * factor);
    const auto [lo, hi] = std::minmax_element(coarse.values.begin(), coarse.values.end());
    for (const double v : fine.values) {
      CHECK((v >= *lo - 1e-15 && v <= *hi + 1e-15));
    }
    // At coarse texel (x, y): the tensor product of (1, 4, 1) / 6, wrapping.
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{15, 3}, std::pair{7, 15}}) {
      double expected = 0.0;
      for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
          const double w = (i == 0 ? 4.0 : 1.0) * (j == 0 ? 4.0 : 1.0) / 36.0;
          expected += w * coarse.at((x + i + 16) % 16, (y + j + 16) % 16);
        }
      }
      CHECK(fine.at(x * factor, y * factor) == Approx(expected).epsilon(1e-12));
    }
    // The mean of a periodic grid is kept (every coarse texel's weights sum to 1 over a period).
    CHECK(mean_of(fine) == Approx(mean_of(coarse)).epsilon(1e-12));
  }
  GreyGrid flat;
  flat.side = 8;
  flat.values.assign(64, 0.375);
  for (const double v : bspline_refine(flat, 4).values) {
    CHECK(v == Approx(0.375).epsilon(1e-15));
  }
  // A smooth image: one period of a sine over 64 texels along x. Sampled with the quintic fade
  // the slope falls to 0 at every texel (a terrace per texel); refined 4x and sampled linearly
  // it follows the sine's slope to a few percent.
  GreyGrid wave;
  wave.side = 64;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      wave.values.push_back(std::sin(2.0 * std::numbers::pi * x / 64.0));
    }
  }
  const GreyGrid refined = bspline_refine(wave, 4);
  double worst_quintic = 0.0, worst_refined = 0.0;
  for (int s = 0; s < 64 * 16; ++s) {
    const double x = s / 16.0 + 1.0 / 32.0;  // texel units of the coarse grid
    const double true_slope =
        2.0 * std::numbers::pi / 64.0 * std::cos(2.0 * std::numbers::pi * x / 64.0);
    const int i = int(std::floor(x));
    const double t = x - i;
    const double quintic_slope =
        (wave.at((i + 1) % 64, 0) - wave.at(i % 64, 0)) * fade_slope<Interpolant::kQuintic>(t);
    const double fx = x * 4.0;
    const int fi = int(std::floor(fx));
    const double linear_slope = (refined.at((fi + 1) % 256, 0) - refined.at(fi % 256, 0)) * 4.0;
    worst_quintic = std::max(worst_quintic, std::abs(quintic_slope - true_slope));
    worst_refined = std::max(worst_refined, std::abs(linear_slope - true_slope));
  }
  const double peak_slope = 2.0 * std::numbers::pi / 64.0;
  INFO("worst slope error: quintic " << worst_quintic / peak_slope << ", refined "
                                     << worst_refined / peak_slope << " of the peak slope");
  CHECK(worst_quintic > 0.8 * peak_slope);   // the terraces: slope 0 where the sine's is peak
  CHECK(worst_refined < 0.03 * peak_slope);  // the smoothing's 1 - pi^2/96/... and the chords
}

TEST_CASE("anUpsampledBasisGridIsTheRefinedCompositionAndSpansTheSameTile", "[basis]") {
  const Scene scene = resolve_scene("craters", {"terrain.basis.upsample=1"});
  const Scene refined_scene = resolve_scene("craters", {"terrain.basis.upsample=4"});
  const std::optional<NoiseLattice> plain = load_basis_grid(scene);
  const std::optional<NoiseLattice> refined = load_basis_grid(refined_scene);
  REQUIRE((plain && refined));
  REQUIRE(refined->size == 4 * plain->size);
  CHECK(refined->min_value >= plain->min_value);
  CHECK(refined->max_value <= plain->max_value);
  // The tile's world size is the same: 4x the texels, a quarter the cell.
  CHECK(stage3_terrain(refined_scene.terrain, refined->size).horizontal_scale ==
        stage3_terrain(scene.terrain, plain->size).horizontal_scale / 4.0);
}

}  // namespace
}  // namespace relief
