// A height field's levels of detail (core/height_sketch.h, build_field_levels).
#include <algorithm>
#include <utility>
#include <vector>

#include "core/height_sketch.h"
#include "core/limits.h"

namespace relief {

namespace {

// The sides of the levels build_field_levels makes from a width x height field.
std::vector<std::pair<int, int>> field_level_sides(int width, int height) {
  std::vector<std::pair<int, int>> sides = {{width, height}};
  while (int(sides.size()) < limits::kMaxFieldLevels) {
    const auto [w, h] = sides.back();
    if (w / 2 + 1 >= w && h / 2 + 1 >= h) {
      break;  // 2 x 2 (or 2 wide and 2 high): no side shrinks any more
    }
    sides.push_back({w / 2 + 1, h / 2 + 1});
  }
  return sides;
}

}  // namespace

std::size_t field_levels_samples(int width, int height) {
  std::size_t total = 0;
  for (const auto& [w, h] : field_level_sides(width, height)) {
    total += std::size_t(w) * std::size_t(h);
  }
  return total;
}

void build_field_levels(HeightSketch& field) {
  const std::vector<std::pair<int, int>> sides = field_level_sides(field.width, field.height);
  field.heights.reserve(field_levels_samples(field.width, field.height));
  field.level_width = {field.width};
  field.level_height = {field.height};
  field.level_offset = {0};
  for (std::size_t l = 1; l < sides.size(); ++l) {
    const auto [w, h] = sides[l - 1];
    const auto [next_w, next_h] = sides[l];
    const std::size_t from = field.level_offset.back();
    // Row z of level l - 1 filtered along x at its even columns 2i (taps clamped to the edge),
    // in double; five such rows give one row of level l.
    const auto filter_row = [&](int z, std::vector<double>& out) {
      const float* row = field.heights.data() + from +
                         std::size_t(std::min(std::max(z, 0), h - 1)) * std::size_t(w);
      const auto at = [&](int i) { return double(row[std::min(std::max(i, 0), w - 1)]); };
      for (int i = 0; i < next_w; ++i) {
        const int x = 2 * i;
        out[std::size_t(i)] =
            (at(x - 2) + 4.0 * at(x - 1) + 6.0 * at(x) + 4.0 * at(x + 1) + at(x + 2)) / 16.0;
      }
    };
    std::vector<std::vector<double>> rows(5, std::vector<double>(std::size_t(next_w)));
    const std::size_t offset = field.heights.size();
    field.heights.resize(offset + std::size_t(next_w) * std::size_t(next_h));
    for (int j = 0; j < next_h; ++j) {
      for (int m = 0; m < 5; ++m) {
        filter_row(2 * j + m - 2, rows[std::size_t(m)]);
      }
      float* out = field.heights.data() + offset + std::size_t(j) * std::size_t(next_w);
      for (int i = 0; i < next_w; ++i) {
        const std::size_t c = std::size_t(i);
        out[i] = static_cast<float>(
            (rows[0][c] + 4.0 * rows[1][c] + 6.0 * rows[2][c] + 4.0 * rows[3][c] + rows[4][c]) /
            16.0);
      }
    }
    field.level_width.push_back(next_w);
    field.level_height.push_back(next_h);
    field.level_offset.push_back(offset);
  }
}

}  // namespace relief
