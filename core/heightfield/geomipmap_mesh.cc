// GeoMipMapping's stitched triangle list (core/heightfield/geomipmap.h), its triangles from
// core/heightfield/geomipmap_triangles.h.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/heightfield/geomipmap.h"
#include "core/heightfield/geomipmap_triangles.h"

namespace relief::geomipmap {
namespace {

struct MeshBuilder {
  Mesh& mesh;
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  int c0 = 0, r0 = 0;  // the current tile's first lattice point

  // Lattices are at most kMaxLatticeSide a side (build_geomipmap): ids fit 32 bits.
  std::uint32_t vertex(LatticeStep p) {
    const int c = c0 + p[0], r = r0 + p[1];
    const std::uint64_t key = (static_cast<std::uint64_t>(r) << 32) | static_cast<std::uint32_t>(c);
    const auto [it, inserted] = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size()));
    if (inserted) {
      mesh.vertex_column.push_back(c);
      mesh.vertex_row.push_back(r);
    }
    return it->second;
  }
  void operator()(LatticeStep a, LatticeStep b, LatticeStep c) {
    mesh.indices.push_back(vertex(a));
    mesh.indices.push_back(vertex(b));
    mesh.indices.push_back(vertex(c));
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
  MeshBuilder builder{mesh, {}};
  const auto level_at = [&](int tx, int tz) {
    if (tx < 0 || tz < 0 || tx >= map.tiles_x || tz >= map.tiles_z)
      return -1;
    return selection.level[static_cast<std::size_t>(tz) * map.tiles_x + tx];
  };
  for (int tz = 0; tz < map.tiles_z; ++tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      if (!selection.drawn[static_cast<std::size_t>(tz) * map.tiles_x + tx])
        continue;
      const int level = level_at(tx, tz);
      // Each side at the coarser spacing of the two tiles that share it, drawn or not (the
      // field's edge: this tile's own).
      const auto side = [&](int nx, int nz) { return 1 << std::max(level, level_at(nx, nz)); };
      mesh.tiles.push_back(static_cast<std::uint32_t>(tz * map.tiles_x + tx));
      mesh.tile_first_triangle.push_back(static_cast<std::uint32_t>(mesh.indices.size() / 3));
      builder.c0 = tx * map.tile_cells;
      builder.r0 = tz * map.tile_cells;
      tile_triangles(map.tile_cells, 1 << level,
                     {side(tx, tz - 1), side(tx + 1, tz), side(tx, tz + 1), side(tx - 1, tz)},
                     builder);
    }
  }
  mesh.tile_first_triangle.push_back(static_cast<std::uint32_t>(mesh.indices.size() / 3));
  return mesh;
}

}  // namespace relief::geomipmap
