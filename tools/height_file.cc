#include "tools/height_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/input_file.h"
#include "image/image_io.h"
#include "tools/float_image_file.h"

namespace relief {

std::optional<HeightFormat> height_format(const std::string& name) {
  if (has_extension(name, ".png")) {
    return HeightFormat::kPng16;
  }
  if (has_extension(name, ".r16") || has_extension(name, ".raw")) {
    return HeightFormat::kRaw16;
  }
  if (has_extension(name, ".tif") || has_extension(name, ".tiff")) {
    return HeightFormat::kGeoTiff;
  }
  if (const std::optional<FloatFormat> f = float_format_of(name)) {
    return *f == FloatFormat::kPfm ? HeightFormat::kPfm : HeightFormat::kExr;
  }
  return std::nullopt;
}

std::uint16_t height_level(double height, double low, double high) {
  const double scale = high > low ? 65535.0 / (high - low) : 0.0;  // the division's domain
  const double level = std::round((height - low) * scale);
  return static_cast<std::uint16_t>(std::clamp(level, 0.0, 65535.0));
}

std::vector<unsigned char> encode_heights(HeightFormat format, int width, int height,
                                          std::span<const float> heights, double low, double high,
                                          std::span<const ImageText> text) {
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  if (holds_levels(format)) {
    std::vector<std::uint16_t> levels(w * h);
    std::transform(heights.begin(), heights.end(), levels.begin(),
                   [&](float v) { return height_level(v, low, high); });
    if (format == HeightFormat::kPng16) {
      return encode_png_grey16_with_text(width, height, levels, text);
    }
    std::vector<unsigned char> out(2 * levels.size());  // little-endian, top row first
    for (std::size_t k = 0; k < levels.size(); ++k) {
      out[2 * k] = static_cast<unsigned char>(levels[k] & 0xFF);
      out[2 * k + 1] = static_cast<unsigned char>(levels[k] >> 8);
    }
    return out;
  }
  // Float files store rows bottom to top (float_image_file.h): z = height - 1 first, so that
  // every format shows the same picture, z0 at the top.
  std::vector<float> rows(w * h);
  for (std::size_t z = 0; z < h; ++z) {
    std::copy_n(heights.begin() + std::ptrdiff_t(z * w), w,
                rows.begin() + std::ptrdiff_t((h - 1 - z) * w));
  }
  return encode_float_image(format == HeightFormat::kPfm ? FloatFormat::kPfm : FloatFormat::kExr,
                            width, height, 1, rows, w, text);
}

}  // namespace relief
