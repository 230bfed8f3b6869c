// What relief compare prints and writes about a comparison (image_compare.h): the report as
// text, in idiff's lines so that whoever reads idiff's output reads it too; the same as JSON;
// and a heat map of the differences.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/image_compare.h"
#include "tools/image_file.h"

namespace relief {

struct CompareReport {
  std::string a_name, b_name;     // as given on the command line
  const FloatImage* a = nullptr;  // null when the comparison did not read the pixels
  const FloatImage* b = nullptr;
  CompareThresholds thresholds;
  CompareResult result;
  // NaN and infinite channel values of each image (count_non_finite, image_file.h): idiff's
  // verdict ignores a NaN difference, so the report says how many there are.
  NonFiniteCount a_non_finite, b_non_finite;
};

// idiff's report: "Comparing "A" and "B"", the size and channels, "Mean error = ...", "RMS
// error = ...", "Peak SNR = ...", "Max error  = ... @ (x, y, channel)  values are ... vs ...",
// the pixels over the warning and then the failure threshold, a line for each image holding
// NaN or infinite values (not idiff's: it says nothing of them), and the verdict's name last.
// Numbers as idiff prints them (%g: six significant digits; "inf", "nan").
void print_compare_report(std::ostream& out, const CompareReport& report);

// The same figures as JSON, at full precision; PSNR is null when the images are equal
// (infinite), a figure that is NaN is null too; "non_finite" counts each image's NaN and
// infinite channel values.
nlohmann::json compare_report_json(const CompareReport& report);

// The diff heat map's scale: the largest difference is red, differences kHeatDecades decades
// smaller or less are dark blue, logarithmic between (a few outliers beside a little noise both
// show); equal pixels are black, NaN magenta (colormap.h).
inline constexpr double kHeatDecades = 4;

// The heat map of `difference` (largest_channel_difference, rows top first) as PNG bytes.
std::vector<unsigned char> difference_heat_map_png(const std::vector<float>& difference, int width,
                                                   int height);

}  // namespace relief
