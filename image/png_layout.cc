#include "image/png_layout.h"

#include <algorithm>
#include <span>

#include "image/crc32.h"

namespace relief {

namespace {

std::uint32_t big_endian(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 |
         std::uint32_t{p[3]};
}

// A chunk type for a message: its four bytes when they are letters (§5.4), else their hex.
std::string chunk_name(const unsigned char* type) {
  const bool letters = std::all_of(type, type + 4, [](unsigned char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
  });
  if (letters) {
    return std::string(type, type + 4);
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex = "0x";
  for (int k = 0; k < 4; ++k) {
    hex += kHex[type[k] >> 4];
    hex += kHex[type[k] & 15];
  }
  return hex;
}

}  // namespace

PngLayout png_layout(const unsigned char* bytes, std::size_t size, bool check_crc) {
  static constexpr std::uint32_t kMaxChunkLength = 0x7fffffff;  // §5.3
  PngLayout layout;
  std::size_t at = 8;  // after the signature
  for (;;) {
    if (size - at < 12) {
      layout.problem = "the file ends at byte " + std::to_string(size) +
                       " inside a chunk header, before the IEND chunk (it is truncated)";
      return layout;
    }
    const std::uint32_t length = big_endian(bytes + at);
    const std::string name = chunk_name(bytes + at + 4);
    if (length > kMaxChunkLength) {
      layout.problem = "chunk " + name + " at byte " + std::to_string(at) + " has length " +
                       std::to_string(length) + "; PNG allows at most 2^31 - 1";
      return layout;
    }
    if (length > size - at - 12) {
      layout.problem = "chunk " + name + " at byte " + std::to_string(at) + " has " +
                       std::to_string(length) + " data bytes, but only " +
                       std::to_string(size - at - 12) + " follow (the file is truncated)";
      return layout;
    }
    if (name == "IDAT" && length == 0 && layout.image_data.empty()) {
      // Valid PNG, but stb_image copies its no bytes to a null buffer (undefined behaviour,
      // found by the texture fuzzer); no encoder writes it.
      layout.problem = "chunk IDAT at byte " + std::to_string(at) +
                       " is empty and comes before the image data (not supported)";
      return layout;
    }
    if (check_crc &&
        crc32(std::span<const unsigned char>(bytes + at + 4, std::size_t{length} + 4)) !=
            big_endian(bytes + at + 8 + length)) {
      layout.problem = "chunk " + name + " at byte " + std::to_string(at) +
                       " does not match its CRC-32 (the file is damaged)";
      return layout;
    }
    if (name == "IDAT") {
      layout.image_data.insert(layout.image_data.end(), bytes + at + 8, bytes + at + 8 + length);
    }
    at += 12 + std::size_t{length};
    if (name == "IEND") {
      return layout;
    }
  }
}

std::uint64_t png_filtered_image_bytes(const PngHeader& header, bool interlaced) {
  int channels = 0;
  bool depth_allowed = false;
  const int d = header.bit_depth;
  switch (header.colour_type) {
    case 0:  // greyscale
      channels = 1;
      depth_allowed = d == 1 || d == 2 || d == 4 || d == 8 || d == 16;
      break;
    case 3:  // palette indices
      channels = 1;
      depth_allowed = d == 1 || d == 2 || d == 4 || d == 8;
      break;
    case 2:  // RGB
    case 4:  // greyscale + alpha
    case 6:  // RGBA
      channels = header.colour_type == 2 ? 3 : header.colour_type == 4 ? 2 : 4;
      depth_allowed = d == 8 || d == 16;
      break;
    default:
      break;
  }
  if (!depth_allowed) {
    return 0;
  }
  const auto image_bytes = [&](std::uint64_t width, std::uint64_t height) -> std::uint64_t {
    if (width == 0 || height == 0) {
      return 0;  // an empty Adam7 pass has no rows, not even filter bytes
    }
    return height * (1 + (width * channels * std::uint64_t(d) + 7) / 8);
  };
  const std::uint64_t w = header.width, h = header.height;
  if (!interlaced) {
    return image_bytes(w, h);
  }
  // Adam7's passes: origin and spacing of each reduced image (§8.2).
  static constexpr int kX0[7] = {0, 4, 0, 2, 0, 1, 0}, kDx[7] = {8, 8, 4, 4, 2, 2, 1};
  static constexpr int kY0[7] = {0, 0, 4, 0, 2, 0, 1}, kDy[7] = {8, 8, 8, 4, 4, 2, 2};
  std::uint64_t total = 0;
  for (int p = 0; p < 7; ++p) {
    const std::uint64_t pw = w > std::uint64_t(kX0[p]) ? (w - kX0[p] + kDx[p] - 1) / kDx[p] : 0;
    const std::uint64_t ph = h > std::uint64_t(kY0[p]) ? (h - kY0[p] + kDy[p] - 1) / kDy[p] : 0;
    total += image_bytes(pw, ph);
  }
  return total;
}

}  // namespace relief
