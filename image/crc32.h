// CRC-32 as PNG chunks carry it (ISO/IEC 15948 §5.3 and Annex D): the reflected polynomial
// 0xEDB88320 of ISO 3309 / ITU-T V.42, register preset to all ones and inverted at the end.
// crc32("123456789") = 0xCBF43926, the standard check value (tests/image/png_text_test.cc).
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace relief {

namespace detail {

constexpr std::array<std::uint32_t, 256> make_crc32_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) {
      c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    table[n] = c;
  }
  return table;
}

inline constexpr std::array<std::uint32_t, 256> kCrc32Table = make_crc32_table();

}  // namespace detail

// The CRC of `bytes` continued from `crc` (the CRC of the bytes before them; 0 to start), so
// that a chunk's type and data can be fed in two parts.
constexpr std::uint32_t crc32(std::span<const unsigned char> bytes, std::uint32_t crc = 0) {
  std::uint32_t c = crc ^ 0xFFFFFFFFu;
  for (const unsigned char b : bytes) {
    c = detail::kCrc32Table[(c ^ b) & 0xFFu] ^ (c >> 8);
  }
  return c ^ 0xFFFFFFFFu;
}

}  // namespace relief
