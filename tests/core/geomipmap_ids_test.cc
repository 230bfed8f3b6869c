// GeoMipMapping's stable triangle numbers (core/heightfield/geomipmap.h, Mesh::tile_first_id,
// stable_primitive_ids): a mesh whose selection occluded some tiles numbers each triangle as the
// mesh with those tiles drawn does. The oracle compares geometry: the triangle the stable number
// names in the whole mesh has the same three lattice points.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

std::array<std::array<int, 2>, 3> triangle_points(const Mesh& mesh, std::uint32_t t) {
  std::array<std::array<int, 2>, 3> p{};
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t v = mesh.indices[3 * std::size_t(t) + i];
    p[std::size_t(i)] = {mesh.vertex_column[v], mesh.vertex_row[v]};
  }
  return p;
}

TEST_CASE("occludedTilesKeepTheMeshsTriangleNumbersStable", "[geomipmap]") {
  const int tiles_x = 6, tiles_z = 5, cells = 8;
  const int columns = tiles_x * cells + 1, rows = tiles_z * cells + 1;
  const std::vector<float> heights(std::size_t(columns) * rows, 0.0f);
  const GeoMipMap map = build_geomipmap({columns, rows, {0.0, 0.0, 48.0, 40.0}, heights}, cells);
  for (int trial = 0; trial < 12; ++trial) {
    Selection whole;  // levels within one of their neighbours', a few tiles culled
    whole.level.resize(map.tiles.size());
    whole.drawn.assign(map.tiles.size(), 1);
    for (std::size_t t = 0; t < map.tiles.size(); ++t) {
      const int tx = int(t) % tiles_x, tz = int(t) / tiles_x;
      whole.level[t] = (tx + tz + trial) % 3;
      whole.drawn[t] = (t * 7 + std::size_t(trial)) % 11 != 0 ? 1 : 0;
    }
    Selection occluded = whole;
    occluded.occluded.assign(map.tiles.size(), 0);
    for (std::size_t t = 0; t < map.tiles.size(); ++t) {
      if (whole.drawn[t] != 0 && (t * 5 + std::size_t(trial)) % 4 == 0) {
        occluded.drawn[t] = 0;
        occluded.occluded[t] = 1;
      }
    }
    const Mesh full = stitched_mesh(map, whole), part = stitched_mesh(map, occluded);
    INFO("trial " << trial);
    REQUIRE(part.indices.size() < full.indices.size());
    // The whole mesh numbers its triangles in order; the end is the same in both.
    CHECK(full.tile_first_id == full.tile_first_triangle);
    CHECK(part.tile_first_id.back() == full.tile_first_triangle.back());
    std::vector<std::uint32_t> ids(part.indices.size() / 3);
    for (std::uint32_t t = 0; t < ids.size(); ++t) {
      ids[t] = t;
    }
    ids.push_back(0xffffffffu);  // no triangle: kept
    stable_primitive_ids(part, ids);
    CHECK(ids.back() == 0xffffffffu);
    for (std::uint32_t t = 0; t + 1 < ids.size(); ++t) {
      REQUIRE(ids[t] < full.indices.size() / 3);
      REQUIRE(triangle_points(part, t) == triangle_points(full, ids[t]));
    }
  }
}

}  // namespace
}  // namespace relief::geomipmap
