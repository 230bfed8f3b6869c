#include "tools/image_compare.h"

#include "tools/image_library.h"

namespace relief {

namespace {

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
  // OpenImageIO's ImageBufAlgo::compare (image_library.h), serially: the same figures on every
  // run.
  CompareResult figures = image_library().compare(a, b, thresholds.fail, thresholds.warn);
  figures.pixels = static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
  figures.verdict = verdict(figures, thresholds);
  return figures;
}

std::vector<float> largest_channel_difference(const FloatImage& a, const FloatImage& b) {
  return image_library().largest_channel_difference(a, b);
}

}  // namespace relief
