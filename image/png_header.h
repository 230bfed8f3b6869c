// The fixed start of every PNG file (ISO/IEC 15948 §5.2, §11.2.2): the 8-byte signature and
// the IHDR chunk, read before the rest of the file so that a file can be refused by its size,
// bit depth or colour type without decoding it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "image/byte_order.h"

namespace relief {

struct PngHeader {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int bit_depth = 0;    // bits per channel (per palette index for colour type 3)
  int colour_type = 0;  // 0 grey, 2 RGB, 3 palette, 4 grey + alpha, 6 RGBA
  int interlace = 0;    // 0 none, 1 Adam7 (§8.2)
};

// The first kPngHeaderBytes bytes of a file.
inline constexpr std::size_t kPngHeaderBytes = 33;

// nullopt when the bytes do not start with the PNG signature followed by an IHDR chunk.
inline std::optional<PngHeader> parse_png_header(const unsigned char* bytes, std::size_t size) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size < kPngHeaderBytes) {
    return std::nullopt;
  }
  for (int k = 0; k < 8; ++k) {
    if (bytes[k] != kSignature[k]) {
      return std::nullopt;
    }
  }
  const auto big_endian = [&](std::size_t at) { return read_big_endian_u32(bytes + at); };
  if (big_endian(8) != 13 || bytes[12] != 'I' || bytes[13] != 'H' || bytes[14] != 'D' ||
      bytes[15] != 'R') {
    return std::nullopt;
  }
  return PngHeader{big_endian(16), big_endian(20), bytes[24], bytes[25], bytes[28]};
}

}  // namespace relief
