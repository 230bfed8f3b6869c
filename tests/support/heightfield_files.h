// Height-field files written byte by byte in the tests, not by Relief's encoders, so that the
// readers (pipeline/heightfield_files.h) are checked against the formats themselves.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "tests/support/test_support.h"

namespace relief::test {

// `count` samples uniform in [0, 1) from the fixed-seed TestRandom: a rough field for a PFM.
inline std::vector<float> random_unit_samples(std::size_t count, unsigned seed) {
  std::vector<float> values(count);
  TestRandom rng(seed);
  for (float& v : values) {
    v = float(rng.uniform(0.0, 1.0));
  }
  return values;
}

// A one-channel PFM (or `magic` PF), samples given top row first.
inline std::string pfm_bytes(int width, int height, const std::vector<float>& top_row_first,
                             bool little_endian = true, const std::string& magic = "Pf") {
  std::string out = magic + "\n" + std::to_string(width) + " " + std::to_string(height) + "\n" +
                    (little_endian ? "-1.0" : "1.0") + "\n";
  for (int j = height - 1; j >= 0; --j) {  // PFM: bottom row first
    for (int i = 0; i < width; ++i) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &top_row_first[std::size_t(j * width + i)], 4);
      for (int b = 0; b < 4; ++b) {
        const int shift = little_endian ? 8 * b : 8 * (3 - b);
        out.push_back(static_cast<char>((bits >> shift) & 0xFF));
      }
    }
  }
  return out;
}

inline std::string raw16_bytes(const std::vector<std::uint16_t>& levels) {
  std::string out;
  for (const std::uint16_t v : levels) {
    out.push_back(static_cast<char>(v & 0xFF));
    out.push_back(static_cast<char>(v >> 8));
  }
  return out;
}

}  // namespace relief::test
