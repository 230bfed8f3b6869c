// PNG's integers are 4 bytes, most significant first (ISO/IEC 15948 §7.1): the one place the
// encoder, the text-chunk writer and the header reader turn them into bytes and back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace relief {

inline void append_big_endian_u32(std::vector<unsigned char>& out, std::uint32_t value) {
  out.insert(out.end(),
             {static_cast<unsigned char>(value >> 24), static_cast<unsigned char>(value >> 16),
              static_cast<unsigned char>(value >> 8), static_cast<unsigned char>(value)});
}

// The 4 bytes at `bytes`; the caller has checked that they are there.
inline std::uint32_t read_big_endian_u32(const unsigned char* bytes) {
  return std::uint32_t{bytes[0]} << 24 | std::uint32_t{bytes[1]} << 16 |
         std::uint32_t{bytes[2]} << 8 | std::uint32_t{bytes[3]};
}

}  // namespace relief
