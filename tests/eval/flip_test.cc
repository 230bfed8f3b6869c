// LDR-FLIP (eval/flip.h) and the image error figures (eval/image_error.h): the
// properties the published formulation has, and the figures of cases with a closed form.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "eval/flip.h"
#include "eval/image_error.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kWidth = 48, kHeight = 40;

std::vector<float> uniform(float value) {
  return std::vector<float>(3 * kWidth * kHeight, value);
}

// A test picture with edges, points and colour: a gradient, a bright square and a dot.
std::vector<float> picture() {
  std::vector<float> rgb(3 * kWidth * kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t k = 3 * (std::size_t(y) * kWidth + x);
      const bool square = x > 10 && x < 24 && y > 8 && y < 20;
      const bool dot = x == 35 && y == 25;
      rgb[k] = square ? 0.9f : 0.1f + 0.6f * float(x) / kWidth;
      rgb[k + 1] = dot ? 1.0f : 0.3f;
      rgb[k + 2] = 0.2f + 0.5f * float(y) / kHeight;
    }
  }
  return rgb;
}

// `base` plus `amplitude` times a fixed noise pattern in [-1, 1], clamped to [0, 1].
std::vector<float> with_noise(const std::vector<float>& base, float amplitude) {
  test::TestRandom random(7);
  std::vector<float> out(base.size());
  for (std::size_t k = 0; k < base.size(); ++k) {
    out[k] = std::clamp(base[k] + amplitude * float(random.uniform(-1.0, 1.0)), 0.0f, 1.0f);
  }
  return out;
}

double mean_flip(const std::vector<float>& test, const std::vector<float>& reference) {
  return image_error(test, reference, kWidth, kHeight).mean_flip;
}

TEST_CASE("flipOfIdenticalImagesIsZero", "[flip]") {
  const std::vector<float> a = picture();
  const ImageError e = image_error(a, a, kWidth, kHeight);
  CHECK(e.mean_flip == 0.0);
  CHECK(e.rmse == 0.0);
  CHECK(std::isinf(e.psnr_db));
  CHECK(e.max_error == 0.0);
  for (const float v : e.flip_map) {
    REQUIRE(v == 0.0f);
  }
}

TEST_CASE("flipIsSymmetric", "[flip]") {
  // HyAB and the feature difference are symmetric in their arguments, and both images pass
  // the same filters: swapping them gives the same bits.
  const std::vector<float> a = picture();
  const std::vector<float> b = with_noise(a, 0.1f);
  CHECK(flip_error_map(a, b, kWidth, kHeight, kDefaultPixelsPerDegree) ==
        flip_error_map(b, a, kWidth, kHeight, kDefaultPixelsPerDegree));
}

TEST_CASE("flipGrowsWithTheNoiseAmplitude", "[flip]") {
  const std::vector<float> a = picture();
  double previous = 0;
  for (const float amplitude : {0.005f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
    const double flip = mean_flip(with_noise(a, amplitude), a);
    INFO("noise " << amplitude << ": mean FLIP " << flip);
    CHECK(flip > previous);
    CHECK(flip < 1.0);
    previous = flip;
  }
}

TEST_CASE("flipOfBlackAgainstWhiteIsNearOne", "[flip]") {
  // Uniform images have no features: FLIP is the colour term. HyAB(black, white) = 100 (L*
  // alone), 100^0.7 = 25.1, above pc cmax: 0.95 + (25.1 - 0.4 cmax) / (0.6 cmax) 0.05 = 0.967
  // with cmax = HyAB(green, blue)^0.7 = 41.2 (Hunt-adjusted).
  const std::vector<float> black = uniform(0.0f), white = uniform(1.0f);
  const ImageError e = image_error(black, white, kWidth, kHeight);
  CHECK(e.mean_flip == Approx(0.967).margin(0.002));
  CHECK(e.rmse == Approx(1.0));
  CHECK(e.psnr_db == Approx(0.0).margin(1e-12));
  CHECK(e.max_error == Approx(1.0));
  // A small grey step is far from 1.
  CHECK(mean_flip(uniform(0.5f), uniform(0.52f)) < 0.2);
}

TEST_CASE("pixelsPerDegreeOfTheFlipPapersSetUp", "[flip]") {
  // FLIP's default observer: a 0.7 m wide 3840-pixel monitor at 0.7 m is 67.02 PPD.
  CHECK(pixels_per_degree(0.7, 0.7, 3840) == Approx(67.02).margin(0.005));
  CHECK(kDefaultPixelsPerDegree == Approx(pixels_per_degree(0.7, 0.7, 3840)));
}

TEST_CASE("imageErrorFiguresHaveTheirClosedForms", "[flip]") {
  // One channel of one pixel off by 0.5 in display value: RMSE = 0.5 / sqrt(3 N).
  std::vector<float> a = uniform(0.0f), b = uniform(0.0f);
  b[3 * 5 + 1] = 0.21404114f;  // srgb_encode(0.21404114) = 0.5
  const ImageError e = image_error(b, a, kWidth, kHeight);
  const double n = 3.0 * kWidth * kHeight;
  CHECK(e.max_error == Approx(0.5).epsilon(1e-6));
  CHECK(e.max_pixel == 5);
  CHECK(e.max_channel == 1);
  CHECK(e.rmse == Approx(0.5 / std::sqrt(n)).epsilon(1e-6));
  CHECK(e.psnr_db == Approx(20.0 * std::log10(std::sqrt(n) / 0.5)).epsilon(1e-6));
  // Values beyond [0, 1] and NaN are clamped (an LDR display): they compare as 1 and 0.
  std::vector<float> bright = uniform(7.0f), nan = uniform(std::nanf(""));
  CHECK(image_error(bright, uniform(1.0f), kWidth, kHeight).mean_flip == 0.0);
  CHECK(image_error(nan, uniform(0.0f), kWidth, kHeight).mean_flip == 0.0);
}

}  // namespace
}  // namespace relief
