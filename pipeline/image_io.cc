#include "pipeline/image_io.h"

#include <bit>
#include <cassert>
#include <cstring>
#include <string>

#include <stb_image_write.h>

namespace relief {

namespace {

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* bytes = static_cast<const unsigned char*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<unsigned char> encode_png_rgb(int width, int height, std::span<const std::uint8_t> rgb,
                                          std::span<const ImageText> text) {
  assert(rgb.size() == static_cast<std::size_t>(width) * height * 3);
  const int row_bytes = width * 3;
  // Point stb at the last row and give it a negative stride: top-to-bottom without a copy.
  const std::uint8_t* top_row = rgb.data() + static_cast<std::size_t>(height - 1) * row_bytes;
  std::vector<unsigned char> png;
  stbi_write_png_to_func(append_bytes, &png, width, height, 3, top_row, -row_bytes);
  if (text.empty() || png.empty()) {  // empty: stb_image_write failed (out of memory)
    return png;
  }
  return insert_png_text(png, text);
}

std::vector<unsigned char> encode_pfm(int width, int height, int channels,
                                      std::span<const float> values, std::size_t stride) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
  const std::string header = std::string(channels == 3 ? "PF" : "Pf") + "\n" +
                             std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
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
