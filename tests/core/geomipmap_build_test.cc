// A GeoMipMap's build run through a caller's parallel loop (core/parallel_rows.h): the same map
// as the serial build, bit for bit, and the same refusal.
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

// Every row on a thread of its own, started last row first, so that a row that read or wrote
// another row's tiles would show.
void rows_on_threads(int count, const std::function<void(int)>& body) {
  std::vector<std::thread> running;
  for (int row = count - 1; row >= 0; --row) {
    running.emplace_back([&body, row] { body(row); });
  }
  for (std::thread& t : running) {
    t.join();
  }
}

TEST_CASE("geomipmapBuiltOnThreadsIsTheSerialMapAndNamesTheFirstBadHeight", "[geomipmap]") {
  constexpr int kTileCells = 16, kColumns = 5 * kTileCells + 1, kRows = 3 * kTileCells + 1;
  // Waves of several lengths and a ridge, so that each tile's errors differ from level to level.
  std::vector<float> heights(static_cast<std::size_t>(kColumns) * kRows);
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kColumns; ++c) {
      heights[static_cast<std::size_t>(r) * kColumns + c] =
          static_cast<float>(30.0 * std::sin(0.31 * c) * std::cos(0.23 * r) +
                             7.0 * std::sin(1.7 * c + 0.9 * r) + 40.0 * std::abs(c - 2 * r) / 9.0);
    }
  }
  FieldLattice lattice{kColumns, kRows, {-500.0, -300.0, 500.0, 300.0}, heights};
  const GeoMipMap serial = build_geomipmap(lattice, kTileCells);
  const GeoMipMap threaded = build_geomipmap(lattice, kTileCells, rows_on_threads);
  REQUIRE(threaded.tiles.size() == serial.tiles.size());
  for (std::size_t t = 0; t < serial.tiles.size(); ++t) {
    INFO("tile " << t);
    CHECK(threaded.tiles[t].low == serial.tiles[t].low);
    CHECK(threaded.tiles[t].high == serial.tiles[t].high);
    CHECK(threaded.tiles[t].error == serial.tiles[t].error);
    CHECK(serial.tiles[t].error.back() > 0);
  }
  CHECK(threaded.quadtree_size == serial.quadtree_size);
  REQUIRE(threaded.quadtree.size() == serial.quadtree.size());
  for (std::size_t k = 0; k < serial.quadtree.size(); ++k) {
    REQUIRE(threaded.quadtree[k].size() == serial.quadtree[k].size());
    for (std::size_t n = 0; n < serial.quadtree[k].size(); ++n) {
      CHECK(threaded.quadtree[k][n].low == serial.quadtree[k][n].low);
      CHECK(threaded.quadtree[k][n].high == serial.quadtree[k][n].high);
    }
  }
  // Three bad heights: in the last row of tiles, in the first row's third tile, and in its
  // second tile on an earlier lattice row; row-major, (20, 3) comes first.
  const auto at = [&](int column, int row) -> float& {
    return heights[static_cast<std::size_t>(row) * kColumns + column];
  };
  at(7, 45) = std::numeric_limits<float>::infinity();
  at(40, 9) = std::nanf("");
  at(20, 3) = -std::numeric_limits<float>::infinity();
  CHECK_THROWS_WITH(build_geomipmap(lattice, kTileCells), Catch::Contains("column 20, row 3"));
  CHECK_THROWS_WITH(build_geomipmap(lattice, kTileCells, rows_on_threads),
                    Catch::Contains("column 20, row 3"));
}

}  // namespace
}  // namespace relief::geomipmap
