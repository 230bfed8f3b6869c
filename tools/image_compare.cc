#include "tools/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace relief {

namespace {

// The figures of OpenImageIO 2.4.7's ImageBufAlgo::compare (src/libOpenImageIO/
// imagebufalgo_compare.cpp: compare_ and compare_value), with failrelative = warnrelative = 0
// as idiff passes them, for two float images of one size: so that relief compare and crosscheck
// print the figures idiff prints for the same pair, bit for bit (tests/eval/
// image_difference_test.cc checks them against ImageBufAlgo::compare itself), without loading
// OpenImageIO. What is mirrored, odd as some of it is:
// - the differences are summed in double per batch of 4096 pixels, each batch's sums added to
//   the totals after it, in row order;
// - a difference is taken in float (a - b) and its absolute value then widened to double;
// - a non-finite value equals one of the same kind (NaN and NaN; Inf and Inf of either sign)
//   and is skipped. A mismatch makes the largest difference +inf, at its place, the first time
//   only; once it is inf a mismatch falls through to the sums like any value (its difference
//   inf or NaN: a NaN difference then becomes the largest, and the next difference, whatever it
//   is, replaces it);
// - a pixel warns (fails) once, when some channel's difference is not <= the threshold and its
//   relative difference, difference / mean of |a| and |b| (that mean rounded to float; 0 when
//   the mean is not > 0, as with a NaN or two values whose mean rounds to 0), is not <= 0;
// - the PSNR's peak starts at 1 (float) and is raised to the larger |value| of each compared
//   pair by std::max, whose NaN operand is ignored when it is the second one.
constexpr std::size_t kBatchPixels = 4096;

CompareResult difference_figures(const FloatImage& a, const FloatImage& b, float fail, float warn) {
  CompareResult r;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  const auto channels = static_cast<std::size_t>(a.channels);
  const auto place = [&](std::size_t pixel, std::size_t channel) {
    r.max_x = static_cast<int>(pixel % std::size_t(a.width));
    r.max_y = static_cast<int>(pixel / std::size_t(a.width));
    r.max_channel = static_cast<int>(channel);
  };
  double total = 0;
  double total_squares = 0;
  float peak = 1.0f;
  for (std::size_t batch_start = 0; batch_start < pixels; batch_start += kBatchPixels) {
    double batch = 0;
    double batch_squares = 0;
    const std::size_t batch_end = std::min(pixels, batch_start + kBatchPixels);
    for (std::size_t pixel = batch_start; pixel < batch_end; ++pixel) {
      bool warned = false;
      bool failed = false;
      for (std::size_t c = 0; c < channels; ++c) {
        const float x = a.pixels[pixel * channels + c];
        const float y = b.pixels[pixel * channels + c];
        if (!std::isfinite(x) || !std::isfinite(y)) {
          if (std::isnan(x) == std::isnan(y) && std::isinf(x) == std::isinf(y)) {
            continue;
          }
          if (std::isfinite(r.max_error)) {
            r.max_error = std::numeric_limits<float>::infinity();
            place(pixel, c);
            continue;
          }
        }
        const float abs_x = std::fabs(x);
        const float abs_y = std::fabs(y);
        // OpenImageIO's lerp(abs_x, abs_y, 0.5): in double, returned as float.
        const auto mean_abs = static_cast<float>(double(abs_x) * 0.5 + double(abs_y) * 0.5);
        peak = std::max(peak, std::max(abs_x, abs_y));
        const double difference = std::fabs(x - y);
        const double relative = mean_abs > 0.0 ? difference / mean_abs : 0.0;
        batch += difference;
        batch_squares += difference * difference;
        // Written !(d <= t) so that a NaN difference counts as over.
        if (!(difference <= r.max_error)) {
          r.max_error = difference;
          place(pixel, c);
        }
        if (!warned && !(difference <= warn) && !(relative <= 0.0)) {
          ++r.warn_pixels;
          warned = true;
        }
        if (!failed && !(difference <= fail) && !(relative <= 0.0)) {
          ++r.fail_pixels;
          failed = true;
        }
      }
    }
    total += batch;
    total_squares += batch_squares;
  }
  const auto values = static_cast<double>(pixels * channels);
  r.mean_error = total / values;
  r.rms_error = std::sqrt(total_squares / values);
  r.psnr = 20.0 * std::log10(peak / r.rms_error);
  return r;
}

std::string size_text(const FloatImage& image) {
  return std::to_string(image.width) + " x " + std::to_string(image.height);
}

// idiff's verdict (OIIO 2.4.7 src/idiff/idiff.cpp, main), with -allowfailures 0 and no
// perceptual test. As there, an image with no failing pixel passes even if pixels are over the
// warning thresholds: the warning branch is reached only when some pixel fails but fewer
// than fail_percent do (tests/eval/compare_test.cc checks this against Debian's idiff).
CompareVerdict verdict(const CompareResult& r, const CompareThresholds& t) {
  const double pixels = static_cast<double>(r.pixels);
  if (r.fail_pixels == 0) {
    return CompareVerdict::kPass;
  }
  if (static_cast<double>(r.fail_pixels) > t.fail_percent / 100.0 * pixels ||
      r.max_error > t.hard_fail) {
    return CompareVerdict::kFailure;
  }
  if (static_cast<double>(r.warn_pixels) > t.warn_percent / 100.0 * pixels ||
      r.max_error > t.hard_warn) {
    return CompareVerdict::kWarning;
  }
  return CompareVerdict::kPass;
}

}  // namespace

std::string_view verdict_name(CompareVerdict verdict) {
  switch (verdict) {
    case CompareVerdict::kPass:
      return "PASS";
    case CompareVerdict::kWarning:
      return "WARNING";
    case CompareVerdict::kFailure:
      return "FAILURE";
    case CompareVerdict::kSizeMismatch:
      return "SIZE MISMATCH";
    case CompareVerdict::kFileError:
      break;
  }
  return "FILE ERROR";
}

double CompareResult::warn_percent() const {
  return pixels ? 100.0 * static_cast<double>(warn_pixels) / static_cast<double>(pixels) : 0.0;
}

double CompareResult::fail_percent() const {
  return pixels ? 100.0 * static_cast<double>(fail_pixels) / static_cast<double>(pixels) : 0.0;
}

CompareResult compare_images(const FloatImage& a, const FloatImage& b,
                             const CompareThresholds& thresholds) {
  CompareResult result;
  if (a.width != b.width || a.height != b.height) {
    result.verdict = CompareVerdict::kSizeMismatch;
    result.problem = "the images differ in size: " + size_text(a) + " and " + size_text(b);
    return result;
  }
  if (a.channels != b.channels) {
    result.verdict = CompareVerdict::kFileError;
    result.problem =
        "the images differ in their number of channels: " + std::to_string(a.channels) + " and " +
        std::to_string(b.channels);
    return result;
  }
  if (a.width < 1 || a.height < 1 || a.channels < 1) {
    result.verdict = CompareVerdict::kFileError;
    result.problem =
        "the images are empty (" + size_text(a) + ", " + std::to_string(a.channels) + " channels)";
    return result;
  }
  CompareResult figures = difference_figures(a, b, thresholds.fail, thresholds.warn);
  figures.pixels = static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
  figures.verdict = verdict(figures, thresholds);
  return figures;
}

// ImageBufAlgo::absdiff then maxchan (OpenImageIO 2.4.7, imagebufalgo_pixelmath.cpp and
// imagebufalgo_minmaxchan.cpp), what relief compare's heat map showed when OpenImageIO drew it:
// |a - b| in float per channel, then the running std::max from channel 0, so that a NaN
// difference survives only in channel 0.
std::vector<float> largest_channel_difference(const FloatImage& a, const FloatImage& b) {
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  const auto channels = static_cast<std::size_t>(a.channels);
  std::vector<float> out(pixels, 0.0f);
  for (std::size_t pixel = 0; pixel < pixels && channels > 0; ++pixel) {
    const float* x = a.pixels.data() + pixel * channels;
    const float* y = b.pixels.data() + pixel * channels;
    float largest = std::fabs(x[0] - y[0]);
    for (std::size_t c = 1; c < channels; ++c) {
      largest = std::max(largest, std::fabs(x[c] - y[c]));
    }
    out[pixel] = largest;
  }
  return out;
}

}  // namespace relief
