#include "tools/soup.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/limits.h"
#include "raster/raster_types.h"

namespace relief {

namespace {

// Splits a line into numbers; throws on anything that is not a finite number.
std::vector<double> numbers_of(const std::string& line, const std::string& where) {
  std::vector<double> values;
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    double v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(v)) {
      throw SoupError(where + ": '" + word + "' is not a finite number");
    }
    values.push_back(v);
  }
  return values;
}

}  // namespace

TriangleSoup parse_triangle_soup(std::istream& in, const std::string& name) {
  TriangleSoup soup;
  std::string line;
  int line_number = 0;
  bool have_header = false;
  int first_triangle_line = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string where = name + ":" + std::to_string(line_number);
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) {
      line.erase(hash);
    }
    const std::vector<double> v = numbers_of(line, where);
    if (v.empty()) {
      continue;
    }
    if (!have_header) {
      const int max_side = limits::kMaxViewportSide;
      if (v.size() != 2 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) || v[0] < 1 ||
          v[1] < 1 || v[0] > max_side || v[1] > max_side) {
        throw SoupError(where + ": the header must be 'W H', two integers from 1 to " +
                        std::to_string(max_side));
      }
      soup.width = static_cast<int>(v[0]);
      soup.height = static_cast<int>(v[1]);
      have_header = true;
      continue;
    }
    if (v.size() != 9 && v.size() != 12) {
      throw SoupError(where +
                      ": a triangle is 9 numbers (window x y z per vertex) or 12 (clip x y "
                      "z w per vertex); found " +
                      std::to_string(v.size()));
    }
    const bool clip = v.size() == 12;
    if (first_triangle_line == 0) {
      first_triangle_line = line_number;
      soup.clip_coordinates = clip;
    } else if (clip != soup.clip_coordinates) {
      throw SoupError(where + ": " + (clip ? "clip" : "window") +
                      " coordinates, but the first triangle (line " +
                      std::to_string(first_triangle_line) + ") has " +
                      (soup.clip_coordinates ? "clip" : "window") +
                      " coordinates; use one kind per file");
    }
    const int stride = clip ? 4 : 3;
    for (int k = 0; k < 3; ++k) {
      const double x = v[k * stride], y = v[k * stride + 1], z = v[k * stride + 2];
      const double w = clip ? v[k * stride + 3] : 1.0;
      if (!clip) {
        const double band = raster::kGuardBandPixels;
        if (std::abs(x) > band || std::abs(y) > band) {
          throw SoupError(where + ": vertex " + std::to_string(k) +
                          " lies outside the guard band; allowed |x|, |y| <= 2097152 px");
        }
        if (z < 0.0 || z > 1.0) {
          throw SoupError(where + ": vertex " + std::to_string(k) +
                          " has depth z = " + std::to_string(z) + "; allowed 0 <= z <= 1");
        }
      } else if (std::abs(x) > 1e30 || std::abs(y) > 1e30 || std::abs(z) > 1e30 ||
                 std::abs(w) > 1e30) {
        throw SoupError(where + ": vertex " + std::to_string(k) +
                        " has a coordinate beyond 1e30; allowed |x|, |y|, |z|, |w| <= 1e30");
      }
      soup.indices.push_back(static_cast<std::uint32_t>(soup.x.size()));
      soup.x.push_back(static_cast<float>(x));
      soup.y.push_back(static_cast<float>(y));
      soup.z.push_back(static_cast<float>(z));
      soup.w.push_back(static_cast<float>(w));
    }
  }
  if (!have_header) {
    throw SoupError(name + ": empty; the first line must be the header 'W H'");
  }
  return soup;
}

}  // namespace relief
