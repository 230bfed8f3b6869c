// GeoMipMapping's stitched triangle list (core/heightfield/geomipmap.h), its triangles from
// core/heightfield/geomipmap_triangles.h.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/heightfield/geomipmap.h"
#include "core/heightfield/geomipmap_triangles.h"

namespace relief::geomipmap {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// Vertex ids without a table of the whole lattice: each tile numbers its own (T + 1)^2 points,
// taking the ids of the points it shares from the tiles drawn before it, which in row-major
// order are the tile to its left (its right edge) and the three above (their lower edges: the
// one above, and the corners of the ones above left and above right). A point gets its id
// the first time a triangle uses it, as a map from lattice point to id would give it.
struct MeshBuilder {
  Mesh& mesh;
  int cells = 0;                       // T
  std::vector<std::uint32_t> local;    // (T + 1)^2, this tile's ids, row-major from (c0, r0)
  std::vector<std::uint32_t> above;    // per tile of the previous row: its lower edge (T + 1)
  std::vector<std::uint32_t> current;  // the same for this row
  std::vector<std::uint32_t> right;    // the right edge of the tile just drawn (T + 1)
  int c0 = 0, r0 = 0;                  // the current tile's first lattice point

  std::uint32_t vertex(LatticeStep p) {
    std::uint32_t& id = local[static_cast<std::size_t>(p[1]) * (cells + 1) + p[0]];
    if (id == kNone) {
      // Lattices are at most kMaxLatticeSide a side (build_geomipmap): ids fit 32 bits.
      id = static_cast<std::uint32_t>(mesh.vertex_column.size());
      mesh.vertex_column.push_back(c0 + p[0]);
      mesh.vertex_row.push_back(r0 + p[1]);
    }
    return id;
  }
  void operator()(LatticeStep a, LatticeStep b, LatticeStep c) {
    mesh.indices.push_back(vertex(a));
    mesh.indices.push_back(vertex(b));
    mesh.indices.push_back(vertex(c));
  }
  // Before tile tx of a row: the shared points' ids; `left_drawn`: whether tile tx - 1 was.
  void begin_tile(int tx, int tiles_x, bool left_drawn) {
    const std::size_t side = static_cast<std::size_t>(cells) + 1;
    std::fill(local.begin(), local.end(), kNone);
    const auto take = [](std::uint32_t& to, std::uint32_t from) {
      if (from != kNone)
        to = from;
    };
    for (std::size_t i = 0; i < side; ++i) {
      take(local[i], above[tx * side + i]);  // the upper edge
      if (left_drawn)
        take(local[i * side], right[i]);  // the left edge
    }
    if (tx > 0)
      take(local[0], above[(tx - 1) * side + cells]);  // above left's corner
    if (tx + 1 < tiles_x)
      take(local[cells], above[(tx + 1) * side]);  // above right's corner
  }
  // After it (or in place of an undrawn tile: none of its points has an id).
  void end_tile(int tx, bool drawn) {
    const std::size_t side = static_cast<std::size_t>(cells) + 1;
    for (std::size_t i = 0; i < side; ++i) {
      current[tx * side + i] = drawn ? local[cells * side + i] : kNone;
      right[i] = drawn ? local[i * side + cells] : kNone;
    }
  }
};

}  // namespace

Mesh stitched_mesh(const GeoMipMap& map, const Selection& selection) {
  if (selection.level.size() != map.tiles.size() || selection.drawn.size() != map.tiles.size()) {
    throw std::invalid_argument("selection of " + std::to_string(selection.level.size()) +
                                " tiles for a map of " + std::to_string(map.tiles.size()));
  }
  for (const int level : selection.level) {
    if (level < 0 || level >= map.levels) {
      throw std::invalid_argument("selection level " + std::to_string(level) + "; allowed [0, " +
                                  std::to_string(map.levels - 1) + "]");
    }
  }
  Mesh mesh;
  // At most (T / 2^L + 1)^2 points and 2 (T / 2^L)^2 triangles a drawn tile: reserved once.
  std::size_t most_points = 0, most_triangles = 0;
  for (std::size_t t = 0; t < map.tiles.size(); ++t) {
    if (selection.drawn[t]) {
      const std::size_t cells = static_cast<std::size_t>(map.tile_cells >> selection.level[t]);
      most_points += (cells + 1) * (cells + 1);
      most_triangles += 2 * cells * cells;
    }
  }
  mesh.vertex_column.reserve(most_points);
  mesh.vertex_row.reserve(most_points);
  mesh.indices.reserve(3 * most_triangles);
  const std::size_t points = static_cast<std::size_t>(map.tile_cells) + 1;  // a tile's side
  MeshBuilder builder{mesh,
                      map.tile_cells,
                      std::vector<std::uint32_t>(points * points, kNone),
                      std::vector<std::uint32_t>(points * map.tiles_x, kNone),
                      std::vector<std::uint32_t>(points * map.tiles_x, kNone),
                      std::vector<std::uint32_t>(points, kNone)};
  const auto level_at = [&](int tx, int tz) {
    if (tx < 0 || tz < 0 || tx >= map.tiles_x || tz >= map.tiles_z)
      return -1;
    return selection.level[static_cast<std::size_t>(tz) * map.tiles_x + tx];
  };
  // The stable number of the next triangle: occluded tiles' triangles counted as if drawn.
  std::uint32_t next_id = 0;
  for (int tz = 0; tz < map.tiles_z; ++tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      const std::size_t tile = static_cast<std::size_t>(tz) * map.tiles_x + tx;
      const bool drawn = selection.drawn[tile] != 0;
      const bool occluded = !selection.occluded.empty() && selection.occluded[tile] != 0;
      const int level = level_at(tx, tz);
      // Each side at the coarser spacing of the two tiles that share it, drawn or not (the
      // field's edge: this tile's own).
      const auto side = [&](int nx, int nz) { return 1 << std::max(level, level_at(nx, nz)); };
      const std::array<int, 4> sides = {side(tx, tz - 1), side(tx + 1, tz), side(tx, tz + 1),
                                        side(tx - 1, tz)};
      if (!drawn) {
        if (occluded) {  // the triangles it would have drawn (the levels do not depend on it)
          tile_triangles(map.tile_cells, 1 << level, sides,
                         [&](LatticeStep, LatticeStep, LatticeStep) { ++next_id; });
        }
        builder.end_tile(tx, false);
        continue;
      }
      builder.begin_tile(tx, map.tiles_x, tx > 0 && selection.drawn[tile - 1] != 0);
      mesh.tiles.push_back(static_cast<std::uint32_t>(tile));
      const auto first = static_cast<std::uint32_t>(mesh.indices.size() / 3);
      mesh.tile_first_triangle.push_back(first);
      mesh.tile_first_id.push_back(next_id);
      builder.c0 = tx * map.tile_cells;
      builder.r0 = tz * map.tile_cells;
      tile_triangles(map.tile_cells, 1 << level, sides, builder);
      next_id += static_cast<std::uint32_t>(mesh.indices.size() / 3) - first;
      builder.end_tile(tx, true);
    }
    std::swap(builder.above, builder.current);
  }
  mesh.tile_first_triangle.push_back(static_cast<std::uint32_t>(mesh.indices.size() / 3));
  mesh.tile_first_id.push_back(next_id);
  return mesh;
}

void stable_primitive_ids(const Mesh& mesh, std::span<std::uint32_t> primitive) {
  const std::vector<std::uint32_t>& first = mesh.tile_first_triangle;
  if (first.size() < 2 || mesh.tile_first_id.size() != first.size()) {
    return;  // nothing drawn
  }
  const std::uint32_t end = first.back();
  std::size_t tile = 0;  // neighbouring pixels mostly show one tile: tried first
  for (std::uint32_t& id : primitive) {
    if (id >= end) {
      continue;  // no triangle (kNoPrimitive)
    }
    if (!(first[tile] <= id && id < first[tile + 1])) {
      // The last tile whose first triangle is at most id (first[0] = 0 <= id).
      tile = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), id) -
                                      first.begin()) -
             1;
    }
    id = mesh.tile_first_id[tile] + (id - first[tile]);
  }
}

}  // namespace relief::geomipmap
