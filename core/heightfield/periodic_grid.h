// A periodic square grid of heights (core/heightfield/): the height maps the subdivision and
// Perlin generators make tile the plane, so every neighbour lookup wraps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace relief {

struct PeriodicGrid {
  int side = 0;                // values per row and per column
  std::vector<float> heights;  // side * side, row-major: (x, z) at z * side + x

  PeriodicGrid() = default;
  explicit PeriodicGrid(int s) : side(s), heights(std::size_t(s) * std::size_t(s), 0.0f) {}

  std::size_t index(std::int64_t x, std::int64_t z) const {
    const std::int64_t n = side;
    return std::size_t(((z % n) + n) % n) * std::size_t(side) + std::size_t(((x % n) + n) % n);
  }
  float at(std::int64_t x, std::int64_t z) const { return heights[index(x, z)]; }
  float& at(std::int64_t x, std::int64_t z) { return heights[index(x, z)]; }
};

}  // namespace relief
