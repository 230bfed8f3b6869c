// GeoMipMapping's stitched triangle list (core/heightfield/geomipmap.h).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

struct MeshBuilder {
  const GeoMipMap& map;
  Mesh& mesh;
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  int c0 = 0, r0 = 0;  // the current tile's first lattice point

  std::uint32_t vertex(int u, int v) {
    const int c = c0 + u, r = r0 + v;
    const std::uint64_t key = (static_cast<std::uint64_t>(r) << 32) | static_cast<std::uint32_t>(c);
    const auto [it, inserted] = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size()));
    if (inserted) {
      mesh.vertex_column.push_back(c);
      mesh.vertex_row.push_back(r);
    }
    return it->second;
  }

  // Counter-clockwise seen from +y: the cross product's y, (b - a) x (c - a), positive, with
  // (u, v) along (x, z); a triangle the other way round is emitted as (a, c, b).
  void triangle(std::array<int, 2> a, std::array<int, 2> b, std::array<int, 2> c) {
    const long long cross_y = static_cast<long long>(b[1] - a[1]) * (c[0] - a[0]) -
                              static_cast<long long>(b[0] - a[0]) * (c[1] - a[1]);
    if (cross_y < 0)
      std::swap(b, c);
    mesh.indices.push_back(vertex(a[0], a[1]));
    mesh.indices.push_back(vertex(b[0], b[1]));
    mesh.indices.push_back(vertex(c[0], c[1]));
  }

  // One side of the border ring: the outer edge from t = 0 to T at spacing `edge`, the inner
  // line (offset s inward) from s to T - s at spacing s (one point when s = T / 2), joined by
  // a zipper: each triangle joins the current outer and inner points with the next of one of
  // them, the outer first where its next point is no farther along; both chains are monotone
  // and the inner lies strictly inside, so the triangles tile the trapezoid without overlap.
  template <class At>
  void border(int tile_cells, int s, int edge, At at) {
    std::vector<int> outer, inner;
    for (int t = 0; t <= tile_cells; t += edge)
      outer.push_back(t);
    for (int t = s; t <= tile_cells - s; t += s)
      inner.push_back(t);
    std::size_t a = 0, b = 0;
    while (a + 1 < outer.size() || b + 1 < inner.size()) {
      const bool step_outer =
          a + 1 < outer.size() && (b + 1 == inner.size() || outer[a + 1] <= inner[b + 1]);
      if (step_outer) {
        triangle(at(outer[a], false), at(outer[a + 1], false), at(inner[b], true));
        ++a;
      } else {
        triangle(at(outer[a], false), at(inner[b], true), at(inner[b + 1], true));
        ++b;
      }
    }
  }

  void tile(int tx, int tz, int level, const std::array<int, 4>& edges) {
    const int T = map.tile_cells, s = 1 << level;
    c0 = tx * T;
    r0 = tz * T;
    if (s == T) {
      triangle({0, 0}, {T, 0}, {T, T});
      triangle({0, 0}, {T, T}, {0, T});
      return;
    }
    for (int v = s; v < T - s; v += s) {
      for (int u = s; u < T - s; u += s) {
        triangle({u, v}, {u + s, v}, {u + s, v + s});
        triangle({u, v}, {u + s, v + s}, {u, v + s});
      }
    }
    // edges: the spacing of the sides v = 0, u = T, v = T, u = 0.
    border(T, s, edges[0], [&](int t, bool in) { return std::array<int, 2>{t, in ? s : 0}; });
    border(T, s, edges[1], [&](int t, bool in) { return std::array<int, 2>{in ? T - s : T, t}; });
    border(T, s, edges[2], [&](int t, bool in) { return std::array<int, 2>{t, in ? T - s : T}; });
    border(T, s, edges[3], [&](int t, bool in) { return std::array<int, 2>{in ? s : 0, t}; });
  }
};

}  // namespace

Mesh stitched_mesh(const GeoMipMap& map, const Selection& selection) {
  Mesh mesh;
  MeshBuilder builder{map, mesh, {}};
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
      builder.tile(tx, tz, level,
                   {side(tx, tz - 1), side(tx + 1, tz), side(tx, tz + 1), side(tx - 1, tz)});
    }
  }
  mesh.tile_first_triangle.push_back(static_cast<std::uint32_t>(mesh.indices.size() / 3));
  return mesh;
}

}  // namespace relief::geomipmap
