// GeoTIFFs written byte by byte from the TIFF 6.0 and GeoTIFF 1.1 specifications, not by an
// image library, so that the georeferencing reader (pipeline/geotiff_reference.h) is checked
// against the formats themselves: one float strip, the geo tags given.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace relief::test {

struct GeoTiff {
  int width = 4, height = 3;
  std::vector<float> top_row_first;
  std::vector<double> pixel_scale = {10.0, 10.0, 0.0};                 // 33550; empty: none
  std::vector<double> tie_points = {0, 0, 0, 500000.0, 4200000.0, 0};  // 33922; empty: none
  std::vector<double> transformation;                                  // 34264; empty: none
  std::vector<std::uint16_t> geo_keys;  // 34735 key entries (id, 0, 1, value)...; empty: none
  bool big_endian = false;
};

inline std::string geotiff_bytes(const GeoTiff& g) {
  std::string out;
  const auto put = [&](std::uint64_t v, int n) {
    for (int k = 0; k < n; ++k) {
      const int shift = g.big_endian ? 8 * (n - 1 - k) : 8 * k;
      out.push_back(static_cast<char>((v >> shift) & 0xFF));
    }
  };
  const auto put_double = [&](double d) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &d, 8);
    put(bits, 8);
  };
  std::vector<std::uint16_t> directory;
  if (!g.geo_keys.empty()) {  // header: version 1, revision 1.1, key count
    directory = {1, 1, 1, std::uint16_t(g.geo_keys.size() / 4)};
    directory.insert(directory.end(), g.geo_keys.begin(), g.geo_keys.end());
  }
  // Entries: tag, type (3 SHORT, 4 LONG, 12 DOUBLE), count, value or offset (filled below).
  struct Entry {
    int tag, type;
    std::uint64_t count, value;
  };
  const std::uint64_t samples = std::uint64_t(g.width) * std::uint64_t(g.height);
  std::vector<Entry> entries = {{256, 4, 1, std::uint64_t(g.width)},
                                {257, 4, 1, std::uint64_t(g.height)},
                                {258, 3, 1, 32},
                                {259, 3, 1, 1},
                                {262, 3, 1, 1},
                                {273, 4, 1, 0},  // the strip's offset
                                {277, 3, 1, 1},
                                {278, 4, 1, std::uint64_t(g.height)},
                                {279, 4, 1, 4 * samples},
                                {284, 3, 1, 1},
                                {339, 3, 1, 3}};
  std::vector<std::pair<int, const std::vector<double>*>> doubles;
  for (const auto& [tag, values] :
       {std::pair{33550, &g.pixel_scale}, std::pair{33922, &g.tie_points},
        std::pair{34264, &g.transformation}}) {
    if (!values->empty()) {
      entries.push_back({tag, 12, values->size(), 0});
      doubles.push_back({tag, values});
    }
  }
  if (!directory.empty()) {
    entries.push_back({34735, 3, directory.size(), 0});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
  // Layout: header, directory, then the doubles, the key directory and the strip.
  std::uint64_t at = 8 + 2 + 12 * entries.size() + 4;
  for (Entry& e : entries) {
    if (e.type == 12) {
      e.value = at;
      at += 8 * e.count;
    } else if (e.tag == 34735) {
      e.value = at;
      at += 2 * e.count;
    }
  }
  for (Entry& e : entries) {
    if (e.tag == 273) {
      e.value = at;
    }
  }
  out += g.big_endian ? "MM" : "II";
  put(42, 2);
  put(8, 4);
  put(entries.size(), 2);
  for (const Entry& e : entries) {
    put(std::uint64_t(e.tag), 2);
    put(std::uint64_t(e.type), 2);
    put(e.count, 4);
    if (e.type == 3 && e.count == 1) {  // a SHORT sits left-justified in the value field
      put(e.value, 2);
      put(0, 2);
    } else {
      put(e.value, 4);
    }
  }
  put(0, 4);  // no next directory
  for (const Entry& e : entries) {
    for (const auto& [tag, values] : doubles) {
      if (tag == e.tag) {
        for (const double d : *values) {
          put_double(d);
        }
      }
    }
  }
  for (const std::uint16_t v : directory) {
    put(v, 2);
  }
  for (const float f : g.top_row_first) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    put(bits, 4);
  }
  return out;
}

}  // namespace relief::test
