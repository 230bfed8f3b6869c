// Two float images compared the way OpenImageIO's idiff compares them (OIIO 2.4, Debian 12):
// the figures of ImageBufAlgo::compare (mean, RMS, PSNR, the largest difference and where it
// is, the pixels over the warning and failure thresholds) and idiff's verdict from its
// thresholds, with idiff's exit codes. In memory, so that a command can compare two stages'
// buffers (relief compare reads them from files: image_file.h).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace relief {

// width * height pixels of `channels` floats each, interleaved. Rows in the order the caller
// keeps them: a difference's (x, y) indexes them as stored (image files are read top row
// first, so (x, y) is then where idiff reports it).
struct FloatImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::string> channel_names;  // one a channel ("R", "G", "B"), or empty
  std::vector<float> pixels;               // width * height * channels
};

// idiff's thresholds, options and defaults (idiff --help): a channel's absolute difference
// above `fail` / `warn` makes its pixel a failure / warning; `fail_percent` / `warn_percent`
// of the pixels may fail / warn; any difference above `hard_fail` / `hard_warn` fails / warns
// whatever the percentages. Floats, as idiff holds them, so that a threshold compares with a
// difference exactly as there.
struct CompareThresholds {
  float fail = 1e-6f;
  float fail_percent = 0;
  float hard_fail = std::numeric_limits<float>::infinity();
  float warn = 1e-6f;
  float warn_percent = 0;
  float hard_warn = std::numeric_limits<float>::infinity();
};

// idiff's exit codes (its enum idiffErrors).
enum class CompareVerdict {
  kPass = 0,          // within every threshold
  kWarning = 1,       // over the warning thresholds only
  kFailure = 2,       // over the failure thresholds
  kSizeMismatch = 3,  // the images differ in width or height: nothing compared
  kFileError = 4,     // unreadable, or not comparable (different channel counts)
};

constexpr int exit_code(CompareVerdict verdict) {
  return static_cast<int>(verdict);
}

// The last line of idiff's report: "PASS", "WARNING", "FAILURE"; "SIZE MISMATCH", "FILE ERROR".
std::string_view verdict_name(CompareVerdict verdict);

struct CompareResult {
  CompareVerdict verdict = CompareVerdict::kPass;
  std::string problem;  // why, for kSizeMismatch and kFileError; empty otherwise
  // The figures, over every channel of every pixel (ImageBufAlgo::CompareResults).
  std::uint64_t pixels = 0;  // width * height
  double mean_error = 0;     // mean |a - b|
  double rms_error = 0;      // sqrt(mean (a - b)^2)
  // 20 log10(peak / rms) dB, the peak being 1 or the largest |value| of either image if
  // larger (HDR images); inf when the images are equal.
  double psnr = std::numeric_limits<double>::infinity();
  double max_error = 0;
  // Where max_error is (the first such place in row order; a difference between a finite and
  // a non-finite value is infinite and wins).
  int max_x = 0, max_y = 0, max_channel = 0;
  std::uint64_t warn_pixels = 0;  // pixels with a channel's difference over warn
  std::uint64_t fail_pixels = 0;  // ... over fail
  double warn_percent() const;    // of `pixels`, as idiff prints it
  double fail_percent() const;
};

// Compares a and b. Different widths or heights give kSizeMismatch, different channel counts
// or an empty image kFileError, each with `problem` set and no figures.
CompareResult compare_images(const FloatImage& a, const FloatImage& b,
                             const CompareThresholds& thresholds);

// Per pixel the largest absolute difference of its channels (ImageBufAlgo::absdiff, then
// maxchan), rows as stored; NaN only where channel 0's difference is NaN (NaN against a number,
// or equal infinities, whose difference is inf - inf). a and b have the same
// size and channel count.
std::vector<float> largest_channel_difference(const FloatImage& a, const FloatImage& b);

}  // namespace relief
