// Triangle soups: the text format of `relief raster` (docs/rasteriser.md, "Triangle soups").
//
//   # comment                 ('#' to the end of the line; blank lines are ignored)
//   W H                       framebuffer size, 1..16384
//   x y z  x y z  x y z       a triangle in window coordinates: pixels, depth z in [0, 1]
//   x y z w  x y z w  x y z w a triangle in clip coordinates
//
// One kind per file. Triangle k (0-based, in file order) is primitive k.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace relief {

// A malformed soup; the message names the file, the line and the rule broken.
class SoupError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TriangleSoup {
  int width = 0;
  int height = 0;
  bool clip_coordinates = false;
  std::vector<float> x, y, z, w;       // 3 vertices per triangle; w = 1 for window coordinates
  std::vector<std::uint32_t> indices;  // 0, 1, 2, 3, ...
  std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(indices.size() / 3); }
};

// Reads a soup file: a regular file of at most limits::kMaxSoupFileBytes, lines of at most
// limits::kMaxSoupLineBytes. `check_size(file_bytes)` is called once the file is open and
// before it is parsed (the caller may refuse a file too large for its memory budget by
// throwing). Throws SoupError naming the file (and the line).
TriangleSoup read_triangle_soup(const std::string& path,
                                const std::function<void(std::uintmax_t)>& check_size);

// Parses a soup's bytes exactly as read_triangle_soup parses a file holding them (byte order
// mark, CRs, NUL bytes, line length; no file size limit); `name` starts every message. Throws
// SoupError. The soup fuzzer (fuzz/fuzz_inputs.h) calls it.
TriangleSoup parse_triangle_soup(std::string_view text, const std::string& name);

}  // namespace relief
