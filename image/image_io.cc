#include "image/image_io.h"

#include <bit>
#include <cassert>
#include <cstring>
#include <string>

#include "image/png_encoder.h"

namespace relief {

std::vector<unsigned char> encode_png_rgb(int width, int height, std::span<const std::uint8_t> rgb,
                                          std::span<const ImageText> text) {
  assert(rgb.size() == static_cast<std::size_t>(width) * height * 3);
  std::vector<unsigned char> png = encode_png_rgb8(width, height, rgb);
  if (text.empty() || png.empty()) {  // empty: the compressor failed (out of memory)
    return png;
  }
  return insert_png_text(png, text);
}

std::vector<unsigned char> encode_png_grey16_with_text(int width, int height,
                                                       std::span<const std::uint16_t> levels,
                                                       std::span<const ImageText> text) {
  std::vector<unsigned char> png = encode_png_grey16(width, height, levels);
  if (text.empty() || png.empty()) {
    return png;
  }
  return insert_png_text(png, text);
}

std::string pfm_header(int width, int height, int channels) {
  return std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(width) + " " +
         std::to_string(height) + "\n-1.0\n";
}

std::vector<unsigned char> encode_pfm(int width, int height, int channels,
                                      std::span<const float> values, std::size_t stride) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
  const std::string header = pfm_header(width, height, channels);
  std::vector<unsigned char> out(header.begin(), header.end());
  const std::size_t row_floats = static_cast<std::size_t>(width) * channels;
  out.reserve(out.size() + row_floats * height * sizeof(float));
  for (int j = 0; j < height; ++j) {
    const auto* row = reinterpret_cast<const unsigned char*>(values.data() + j * stride);
    out.insert(out.end(), row, row + row_floats * sizeof(float));
  }
  return out;
}

}  // namespace relief
