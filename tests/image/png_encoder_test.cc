// PNG encoding (image/png_encoder.h) read back by an independent decoder, stb_image: every
// pixel of images of awkward sizes and contents comes back exactly, rows in PNG's top-first
// order; every chunk's CRC holds by the standard's table (image/crc32.h, checked against the
// standard check value in png_text_test.cc); no image is made of no pixels.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <stb_image.h>

#include "image/crc32.h"
#include "image/image_io.h"
#include "image/png_encoder.h"

namespace relief {
namespace {

std::uint32_t be32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

// Decodes with stb_image and returns the rows bottom first, as Relief stores them.
std::vector<std::uint8_t> decode_bottom_up(const std::vector<unsigned char>& png, int width,
                                           int height) {
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
  REQUIRE(pixels != nullptr);
  CHECK(w == width);
  CHECK(h == height);
  CHECK(channels == 3);
  const std::size_t row = std::size_t(width) * 3;
  std::vector<std::uint8_t> out(row * height);
  for (int y = 0; y < height; ++y) {
    std::memcpy(out.data() + std::size_t(height - 1 - y) * row, pixels + std::size_t(y) * row, row);
  }
  stbi_image_free(pixels);
  return out;
}

void check_chunks(const std::vector<unsigned char>& png) {
  REQUIRE(png.size() > 8);
  std::size_t at = 8;
  std::vector<std::string> types;
  while (at + 12 <= png.size()) {
    const std::uint32_t length = be32(&png[at]);
    REQUIRE(at + 12 + length <= png.size());
    const std::span<const unsigned char> typed(&png[at + 4], length + 4);
    CHECK(crc32(typed) == be32(&png[at + 8 + length]));
    types.emplace_back(reinterpret_cast<const char*>(&png[at + 4]), 4);
    at += 12 + length;
  }
  CHECK(at == png.size());
  REQUIRE(types.size() >= 3);
  CHECK(types.front() == "IHDR");
  CHECK(types.back() == "IEND");
}

TEST_CASE("pngEncodingRoundTripsEveryPixelThroughAnIndependentDecoder", "[png]") {
  std::mt19937 random(7);
  const int sizes[][2] = {{1, 1}, {1, 9}, {9, 1}, {2, 3}, {3, 7}, {64, 64}, {257, 129}};
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    INFO(w << " x " << h);
    const std::size_t n = std::size_t(w) * h * 3;
    // Noise (every byte value, Sub's wrap-around), a ramp and a constant image.
    std::vector<std::uint8_t> noise(n), ramp(n), flat(n, 255);
    for (std::size_t k = 0; k < n; ++k) {
      noise[k] = static_cast<std::uint8_t>(random());
      ramp[k] = static_cast<std::uint8_t>(k * 7 + k / 3);
    }
    for (const std::vector<std::uint8_t>* image : {&noise, &ramp, &flat}) {
      const std::vector<unsigned char> png = encode_png_rgb8(w, h, *image);
      check_chunks(png);
      CHECK(decode_bottom_up(png, w, h) == *image);
    }
  }
}

TEST_CASE("pngEncodingWithTextKeepsThePixelsAndTheChunks", "[png]") {
  std::vector<std::uint8_t> rgb(5 * 4 * 3);
  for (std::size_t k = 0; k < rgb.size(); ++k) {
    rgb[k] = static_cast<std::uint8_t>(k * 13);
  }
  const ImageText text[] = {{"relief:test", "value"}};
  const std::vector<unsigned char> png = encode_png_rgb(5, 4, rgb, text);
  check_chunks(png);
  CHECK(decode_bottom_up(png, 5, 4) == rgb);
  CHECK(read_png_text(png).size() == 1);
}

TEST_CASE("pngEncodingRefusesAnImageOfNoPixels", "[png]") {
  CHECK(encode_png_rgb8(0, 4, {}).empty());
  CHECK(encode_png_rgb8(4, 0, {}).empty());
  CHECK(encode_png_rgb8(-1, -1, {}).empty());
}

}  // namespace
}  // namespace relief
