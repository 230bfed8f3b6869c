// terrain.heightfield.interpolating (core/field_prefilter.h): the coefficients' B-spline passes
// through every sample, checked by the test's own evaluation of the B-spline at the texel
// centres (taps clamped to the edge, in double); the same through the sketch's own sampler
// (sample_sketch) once the field is made; the stated overshoot bound; and a field whose samples
// are already a B-spline's values gives back those coefficients.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/field_prefilter.h"
#include "core/height_sketch.h"
#include "tests/support/heightfield_files.h"

namespace relief {
namespace {

// The test's own surface at texel centre (i, j) of coefficients c: the tensor product of
// (c[i-1] + 4 c[i] + c[i+1]) / 6, indices clamped to [0, n - 1].
double surface_at(const std::vector<float>& c, int w, int h, int i, int j) {
  static constexpr double kTaps[3] = {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};
  double sum = 0;
  for (int b = -1; b <= 1; ++b) {
    for (int a = -1; a <= 1; ++a) {
      const int x = std::clamp(i + a, 0, w - 1), z = std::clamp(j + b, 0, h - 1);
      sum += kTaps[a + 1] * kTaps[b + 1] * double(c[std::size_t(z) * w + x]);
    }
  }
  return sum;
}

TEST_CASE("interpolatingCoefficientsPassThroughEverySample", "[core]") {
  for (const auto& [w, h] : {std::pair{2, 2}, {2, 9}, {9, 2}, {17, 5}, {64, 33}, {3, 3}}) {
    INFO(w << " x " << h);
    std::vector<float> samples =
        test::random_unit_samples(std::size_t(w) * std::size_t(h), unsigned(w * 100 + h));
    for (float& v : samples) {
      v = 1000.0f * v - 300.0f;
    }
    std::vector<float> c = samples;
    interpolating_coefficients(c, w, h);
    double worst = 0;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        worst = std::max(
            worst, std::abs(surface_at(c, w, h, i, j) - double(samples[std::size_t(j) * w + i])));
      }
    }
    // Two passes each rounded to float: a few ulps of values below 1e4 (ulp 2^-10 there).
    CHECK(worst < 4e-3);
  }
}

TEST_CASE("anInterpolatingFieldSamplesToItsSamplesAtTexelCentres", "[core]") {
  const int w = 23, h = 14;
  HeightFieldSettings s;
  s.image = "test";
  s.extent = {-100.0, 50.0, 130.0, 190.0};
  s.height = {-40.0, 260.0};
  const std::vector<float> unit = test::random_unit_samples(std::size_t(w) * h, 7);
  const HeightSketch field = make_height_field(s, w, h, unit, false, true);
  const SketchPlan plan = make_sketch_plan(s, field, 0.0, 0.0);
  const SketchParams<double> params = make_sketch_params<double>(plan, &field);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double expected = -40.0 + 300.0 * double(unit[std::size_t(j) * w + i]);
      CHECK(sample_sketch<double>(params, field.heights, i, j) == Approx(expected).margin(2e-3));
    }
  }
  // The bounds are the coefficients' extremes, which enclose every sample.
  CHECK(field.min_height <= -40.0 + 300.0 * *std::min_element(unit.begin(), unit.end()));
  CHECK(field.max_height >= -40.0 + 300.0 * *std::max_element(unit.begin(), unit.end()));
}

TEST_CASE("aCheckerboardsCoefficientsStayWithinTheStatedOvershoot", "[core]") {
  const int w = 40, h = 40;
  std::vector<float> c(std::size_t(w) * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      c[std::size_t(j) * w + i] = ((i + j) % 2 == 0) ? 1.0f : -1.0f;
    }
  }
  interpolating_coefficients(c, w, h);
  const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
  // 9 times the half-range in both axes (field_prefilter.h), the interior's exact value.
  CHECK(*hi <= 9.0f + 1e-4f);
  CHECK(*lo >= -9.0f - 1e-4f);
  CHECK(c[std::size_t(20) * w + 20] == Approx(9.0).margin(1e-3));
}

TEST_CASE("samplesThatAreASplinesValuesGiveBackItsCoefficients", "[core]") {
  const int w = 31, h = 12;
  const std::vector<float> coefficients = test::random_unit_samples(std::size_t(w) * h, 3);
  std::vector<float> values(coefficients.size());
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      values[std::size_t(j) * w + i] = float(surface_at(coefficients, w, h, i, j));
    }
  }
  interpolating_coefficients(values, w, h);
  for (std::size_t k = 0; k < values.size(); ++k) {
    CHECK(values[k] == Approx(coefficients[k]).margin(1e-5));
  }
}

}  // namespace
}  // namespace relief
