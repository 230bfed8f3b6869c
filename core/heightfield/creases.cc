#include "core/heightfield/creases.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

double second_x(const PeriodicGrid& g, int x, int z) {
  return std::abs(double(g.at(x - 1, z)) - 2.0 * g.at(x, z) + double(g.at(x + 1, z)));
}

double second_z(const PeriodicGrid& g, int x, int z) {
  return std::abs(double(g.at(x, z - 1)) - 2.0 * g.at(x, z) + double(g.at(x, z + 1)));
}

}  // namespace

std::vector<float> crease_map(const PeriodicGrid& g) {
  std::vector<float> out(g.heights.size());
  for (int z = 0; z < g.side; ++z) {
    for (int x = 0; x < g.side; ++x) {
      const double h = g.at(x, z);
      const double d1 =
          std::abs(double(g.at(x - 1, z - 1)) - 2.0 * h + double(g.at(x + 1, z + 1))) * 0.5;
      const double d2 =
          std::abs(double(g.at(x - 1, z + 1)) - 2.0 * h + double(g.at(x + 1, z - 1))) * 0.5;
      out[g.index(x, z)] =
          static_cast<float>(std::max({second_x(g, x, z), second_z(g, x, z), d1, d2}));
    }
  }
  return out;
}

double crease_ratio(const PeriodicGrid& g, int levels) {
  double all = 0;
  for (int z = 0; z < g.side; ++z) {
    for (int x = 0; x < g.side; ++x) {
      all += second_x(g, x, z) + second_z(g, x, z);
    }
  }
  const double mean_all = all / (2.0 * double(g.side) * g.side);
  if (!(mean_all > 0)) {
    return 0.0;  // a flat map: no crease, and the ratio's division has no domain
  }
  double on_lines = 0;
  double count = 0;
  for (int l = 1; l <= levels && (g.side >> l) >= 1; ++l) {
    const int spacing = g.side >> l;  // odd multiples of it: the lines level l drew
    for (int line = spacing; line < g.side; line += 2 * spacing) {
      for (int k = 0; k < g.side; ++k) {
        on_lines += second_x(g, line, k) + second_z(g, k, line);
        count += 2;
      }
    }
  }
  return count > 0 ? (on_lines / count) / mean_all : 0.0;
}

double largest_second_difference(const PeriodicGrid& g) {
  double largest = 0;
  for (int z = 0; z < g.side; ++z) {
    for (int x = 0; x < g.side; ++x) {
      largest = std::max({largest, second_x(g, x, z), second_z(g, x, z)});
    }
  }
  return largest;
}

}  // namespace relief
