#include "core/heightfield/smoothing.h"

#include <vector>

namespace relief {

void smooth_height_map(PeriodicGrid& g, int passes, const std::function<void(int, int)>& progress) {
  std::vector<float> line(std::size_t(g.side));
  for (int pass = 0; pass < passes; ++pass) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int row = 0; row < g.side; ++row) {
        // Along x (axis 0) the row's values, along z (axis 1) the column's.
        const auto at = [&](int k) -> float& { return axis == 0 ? g.at(k, row) : g.at(row, k); };
        for (int k = 0; k < g.side; ++k) {
          line[std::size_t(k)] = at(k);
        }
        for (int k = 0; k < g.side; ++k) {
          const double left = line[std::size_t((k + g.side - 1) % g.side)];
          const double right = line[std::size_t((k + 1) % g.side)];
          at(k) = static_cast<float>(0.25 * (left + right) + 0.5 * line[std::size_t(k)]);
        }
      }
    }
    if (progress) {
      progress(pass + 1, passes);
    }
  }
}

}  // namespace relief
