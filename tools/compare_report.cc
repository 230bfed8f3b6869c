#include "tools/compare_report.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <utility>

#include "image/image_io.h"
#include "image/image_metadata.h"
#include "tools/colormap.h"

namespace relief {

namespace {

// printf's %g, which idiff's {:g} equals; idiff spells the non-finite values "inf" and "nan".
std::string g_text(double v) {
  if (std::isnan(v)) {
    return "nan";
  }
  if (std::isinf(v)) {
    return v > 0 ? "inf" : "-inf";
  }
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// A pixel value as idiff prints it: the shortest text that reads back as the same float.
std::string float_text(float v) {
  if (std::isnan(v)) {
    return "nan";
  }
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : "?";
}

std::string channel_name(const CompareReport& r, int channel) {
  const std::vector<std::string>& names = r.a->channel_names;
  return channel >= 0 && std::size_t(channel) < names.size() ? names[std::size_t(channel)]
                                                             : "channel " + std::to_string(channel);
}

std::vector<float> pixel(const FloatImage& image, int x, int y) {
  const auto at =
      (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * std::size_t(image.channels);
  return {image.pixels.begin() + static_cast<std::ptrdiff_t>(at),
          image.pixels.begin() + static_cast<std::ptrdiff_t>(at) + image.channels};
}

std::string joined(const std::vector<float>& values) {
  std::string out;
  for (const float v : values) {
    out += (out.empty() ? "" : ", ") + float_text(v);
  }
  return out;
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// A threshold as it was given (the float's shortest decimal, 0.01 rather than the double
// 0.00999999977648258); "inf" for an infinite one (the hard ones by default): JSON has none.
nlohmann::json threshold(float v) {
  return std::isinf(v) ? nlohmann::json("inf") : nlohmann::json(std::stod(float_text(v)));
}

bool compared(const CompareReport& r) {
  return r.a && r.b && r.result.verdict != CompareVerdict::kSizeMismatch &&
         r.result.verdict != CompareVerdict::kFileError;
}

}  // namespace

void print_compare_report(std::ostream& out, const CompareReport& r) {
  out << "Comparing \"" << r.a_name << "\" and \"" << r.b_name << "\"\n";
  const CompareResult& c = r.result;
  if (!compared(r)) {
    out << "  " << c.problem << "\n" << verdict_name(c.verdict) << "\n";
    return;
  }
  std::string channels;
  for (int k = 0; k < r.a->channels; ++k) {
    channels += (k ? ", " : "") + channel_name(r, k);
  }
  out << "  " << r.a->width << " x " << r.a->height << ", " << r.a->channels << " channels ("
      << channels << ")\n"
      << "  Mean error = " << g_text(c.mean_error) << "\n"
      << "  RMS error = " << g_text(c.rms_error) << "\n"
      << "  Peak SNR = " << g_text(c.psnr) << "\n"
      << "  Max error  = " << g_text(c.max_error);
  if (c.max_error != 0) {
    out << " @ (" << c.max_x << ", " << c.max_y << ", " << channel_name(r, c.max_channel)
        << ")  values are " << joined(pixel(*r.a, c.max_x, c.max_y)) << " vs "
        << joined(pixel(*r.b, c.max_x, c.max_y));
  }
  char percent[32];
  std::snprintf(percent, sizeof percent, "%1.3g", c.warn_percent());
  out << "\n  " << c.warn_pixels << " pixels (" << percent << "%) over "
      << g_text(r.thresholds.warn) << "\n";
  std::snprintf(percent, sizeof percent, "%1.3g", c.fail_percent());
  out << "  " << c.fail_pixels << " pixels (" << percent << "%) over " << g_text(r.thresholds.fail)
      << "\n";
  for (const auto& [name, count] :
       {std::pair{&r.a_name, &r.a_non_finite}, std::pair{&r.b_name, &r.b_non_finite}}) {
    if (count->total() > 0) {
      out << "  \"" << *name << "\" holds " << count->describe()
          << " (the verdict, as idiff's, does not count a NaN difference)\n";
    }
  }
  out << verdict_name(c.verdict) << "\n";
}

nlohmann::json compare_report_json(const CompareReport& r) {
  const CompareResult& c = r.result;
  const CompareThresholds& t = r.thresholds;
  nlohmann::json j = {{"a", r.a_name},
                      {"b", r.b_name},
                      {"thresholds",
                       {{"fail", threshold(t.fail)},
                        {"failpercent", threshold(t.fail_percent)},
                        {"hardfail", threshold(t.hard_fail)},
                        {"warn", threshold(t.warn)},
                        {"warnpercent", threshold(t.warn_percent)},
                        {"hardwarn", threshold(t.hard_warn)}}},
                      {"verdict", verdict_name(c.verdict)},
                      {"exit_code", exit_code(c.verdict)}};
  if (!compared(r)) {
    j["problem"] = c.problem;
    return j;
  }
  std::vector<std::string> names;
  for (int k = 0; k < r.a->channels; ++k) {
    names.push_back(channel_name(r, k));
  }
  j["width"] = r.a->width;
  j["height"] = r.a->height;
  j["channels"] = names;
  j["pixels"] = c.pixels;
  j["mean_error"] = number(c.mean_error);
  j["rms_error"] = number(c.rms_error);
  j["psnr_db"] = number(c.psnr);
  j["max_error"] = number(c.max_error);
  if (c.max_error != 0) {
    nlohmann::json a_values = nlohmann::json::array(), b_values = nlohmann::json::array();
    for (const float v : pixel(*r.a, c.max_x, c.max_y)) {
      a_values.push_back(number(v));
    }
    for (const float v : pixel(*r.b, c.max_x, c.max_y)) {
      b_values.push_back(number(v));
    }
    j["max_error_at"] = {{"x", c.max_x},
                         {"y", c.max_y},
                         {"channel", channel_name(r, c.max_channel)},
                         {"a", a_values},
                         {"b", b_values}};
  }
  j["warn_pixels"] = c.warn_pixels;
  j["warn_percent"] = c.warn_percent();
  j["fail_pixels"] = c.fail_pixels;
  j["fail_percent"] = c.fail_percent();
  j["non_finite"] = {{"a", {{"nan", r.a_non_finite.nan}, {"infinite", r.a_non_finite.infinite}}},
                     {"b", {{"nan", r.b_non_finite.nan}, {"infinite", r.b_non_finite.infinite}}}};
  return j;
}

std::vector<unsigned char> difference_heat_map_png(const std::vector<float>& difference, int width,
                                                   int height) {
  float top = 0;  // the largest finite difference
  for (const float d : difference) {
    top = std::isfinite(d) ? std::max(top, d) : top;
  }
  const double log_top = std::log10(double(top));
  std::vector<std::uint8_t> rgb(difference.size() * 3);
  for (int y = 0; y < height; ++y) {
    // The PNG encoder takes rows bottom first (image_io.h); `difference` has the top first.
    const std::size_t row = std::size_t(height - 1 - y) * std::size_t(width);
    for (int x = 0; x < width; ++x) {
      const float d = difference[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      // d > 0 here, so log10 is finite; an infinite d is above every finite one: red.
      const Rgb8 c = d == 0          ? Rgb8{0, 0, 0}
                     : std::isnan(d) ? heat_color(std::nan(""))
                     : std::isinf(d)
                         ? heat_color(1.0)
                         : heat_color(1.0 + (std::log10(double(d)) - log_top) / kHeatDecades);
      std::copy(c.begin(), c.end(), rgb.begin() + static_cast<std::ptrdiff_t>((row + x) * 3));
    }
  }
  return encode_png_rgb(width, height, rgb, software_metadata());
}

}  // namespace relief
