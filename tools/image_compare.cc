#include "tools/image_compare.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace relief {

namespace {

// An ImageBuf over the image's floats, without a copy. ImageBuf wraps only mutable buffers;
// compare, absdiff and maxchan read their sources and never write them.
OIIO::ImageBuf wrap(const FloatImage& image) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeFloat);
  if (image.channel_names.size() == static_cast<std::size_t>(image.channels)) {
    spec.channelnames = image.channel_names;
  }
  return OIIO::ImageBuf(spec, const_cast<float*>(image.pixels.data()));
}

std::string size_text(const FloatImage& image) {
  return std::to_string(image.width) + " x " + std::to_string(image.height);
}

// idiff's verdict (OIIO 2.4.7 src/idiff/idiff.cpp, main), with -allowfailures 0 and no
// perceptual test. As there, an image with no failing pixel passes even if pixels are over the
// warning thresholds: the warning branch is reached only when some pixel fails but fewer
// than fail_percent do (tests/compare_test.cc checks this against Debian's idiff).
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
  // One thread (OIIO 2.4's compare runs serially anyway, in batches of 4096 pixels): the sums
  // are taken in one fixed order, the figures the same on every run.
  const OIIO::ImageBufAlgo::CompareResults cr = OIIO::ImageBufAlgo::compare(
      wrap(a), wrap(b), thresholds.fail, thresholds.warn, 0.0f, 0.0f, OIIO::ROI::All(), 1);
  // cr.error is set when a pixel fails (OIIO returns "nfail == 0" as success), not on an error:
  // the verdict below decides.
  result.pixels = static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
  result.mean_error = cr.meanerror;
  result.rms_error = cr.rms_error;
  result.psnr = cr.PSNR;
  result.max_error = cr.maxerror;
  result.max_x = cr.maxx;
  result.max_y = cr.maxy;
  result.max_channel = cr.maxc;
  result.warn_pixels = cr.nwarn;
  result.fail_pixels = cr.nfail;
  result.verdict = verdict(result, thresholds);
  return result;
}

std::vector<float> largest_channel_difference(const FloatImage& a, const FloatImage& b) {
  // Every thread: each pixel is computed on its own, the same whichever thread computes it.
  const OIIO::ImageBuf difference =
      OIIO::ImageBufAlgo::absdiff(wrap(a), wrap(b), OIIO::ROI::All(), 0);
  const OIIO::ImageBuf largest = OIIO::ImageBufAlgo::maxchan(difference, OIIO::ROI::All(), 0);
  std::vector<float> out(static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height));
  largest.get_pixels(OIIO::ROI(0, a.width, 0, a.height, 0, 1, 0, 1), OIIO::TypeFloat, out.data());
  return out;
}

}  // namespace relief
