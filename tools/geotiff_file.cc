#include "tools/geotiff_file.h"

#include <cstdint>
#include <cstring>
#include <new>

namespace relief {

namespace {

void put(std::vector<unsigned char>& out, std::uint64_t v, int bytes) {  // little-endian
  for (int k = 0; k < bytes; ++k) {
    out.push_back(static_cast<unsigned char>(v >> (8 * k)));
  }
}

}  // namespace

std::vector<unsigned char> encode_geotiff(int width, int height, std::span<const float> heights,
                                          const std::array<double, 4>& rect) {
  const std::uint64_t samples = std::uint64_t(width) * std::uint64_t(height);
  const double scale[3] = {(rect[2] - rect[0]) / width, (rect[3] - rect[1]) / height, 0.0};
  const double tie[6] = {0.0, 0.0, 0.0, rect[0], -rect[1], 0.0};
  // GeoKeyDirectory: version 1.1.1, 4 keys (id, location 0, count 1, value), sorted by id.
  const std::uint16_t keys[] = {1,    1, 1, 4,      // header
                                1024, 0, 1, 1,      // GTModelTypeGeoKey: projected
                                1025, 0, 1, 1,      // GTRasterTypeGeoKey: PixelIsArea
                                3072, 0, 1, 32767,  // ProjectedCSTypeGeoKey: user-defined
                                3076, 0, 1, 9001};  // ProjLinearUnitsGeoKey: metre
  constexpr int kEntries = 14;
  const std::uint64_t directory = 8, after = directory + 2 + 12 * kEntries + 4;
  const std::uint64_t scale_at = after, tie_at = scale_at + 24, keys_at = tie_at + 48;
  const std::uint64_t strip_at = keys_at + sizeof keys;
  // Tag, type (3 SHORT, 4 LONG, 12 DOUBLE), count, value or offset; ascending tags (TIFF 6.0).
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count;
    std::uint64_t value;
  };
  const Entry entries[kEntries] = {{256, 4, 1, std::uint64_t(width)},
                                   {257, 4, 1, std::uint64_t(height)},
                                   {258, 3, 1, 32},  // BitsPerSample
                                   {259, 3, 1, 1},   // Compression: none
                                   {262, 3, 1, 1},   // PhotometricInterpretation: min is black
                                   {273, 4, 1, strip_at},
                                   {277, 3, 1, 1},  // SamplesPerPixel
                                   {278, 4, 1, std::uint64_t(height)},
                                   {279, 4, 1, 4 * samples},
                                   {284, 3, 1, 1},  // PlanarConfiguration: contiguous
                                   {339, 3, 1, 3},  // SampleFormat: IEEE float
                                   {33550, 12, 3, scale_at},
                                   {33922, 12, 6, tie_at},
                                   {34735, 3, std::uint32_t(std::size(keys)), keys_at}};
  std::vector<unsigned char> out;
  try {
    out.reserve(strip_at + 4 * samples);
  } catch (const std::bad_alloc&) {
    return {};
  }
  out.insert(out.end(), {'I', 'I'});
  put(out, 42, 2);
  put(out, directory, 4);
  put(out, kEntries, 2);
  for (const Entry& e : entries) {
    put(out, e.tag, 2);
    put(out, e.type, 2);
    put(out, e.count, 4);
    put(out, e.value, 4);  // a SHORT sits in the first two bytes: little-endian, the same
  }
  put(out, 0, 4);  // no next directory
  for (const double v : scale) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, 8);
    put(out, bits, 8);
  }
  for (const double v : tie) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, 8);
    put(out, bits, 8);
  }
  for (const std::uint16_t v : keys) {
    put(out, v, 2);
  }
  for (const float v : heights) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    put(out, bits, 4);
  }
  return out;
}

}  // namespace relief
