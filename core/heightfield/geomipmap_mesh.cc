// GeoMipMapping per frame (core/geomipmap.h): the quadtree's frustum culling, each tile's level
// by screen-space error, and the stitched triangle list.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

struct Box {
  glm::dvec3 low, high;  // camera-relative
};

// The tiles [tx0, tx1) x [tz0, tz1) as a box relative to the camera.
Box tile_box(const GeoMipMap& map, const View& view, int tx0, int tz0, int tx1, int tz1, float low,
             float high) {
  const double cells_x = static_cast<double>(map.tiles_x) * map.tile_cells;
  const double cells_z = static_cast<double>(map.tiles_z) * map.tile_cells;
  const auto x_at = [&](int tile) {
    return map.extent[0] +
           (map.extent[2] - map.extent[0]) * (static_cast<double>(tile) * map.tile_cells / cells_x);
  };
  const auto z_at = [&](int tile) {
    return map.extent[1] +
           (map.extent[3] - map.extent[1]) * (static_cast<double>(tile) * map.tile_cells / cells_z);
  };
  return {glm::dvec3(x_at(tx0), low, z_at(tz0)) - view.camera,
          glm::dvec3(x_at(tx1), high, z_at(tz1)) - view.camera};
}

// Outside one plane with every corner: the corner nearest the inside (smallest dot(n, p)) is
// beyond d by more than a relative 1e-9, so rounding never culls a box that touches the
// frustum.
bool outside(const Box& box, const std::vector<glm::dvec4>& planes) {
  for (const glm::dvec4& p : planes) {
    const glm::dvec3 nearest(p.x >= 0 ? box.low.x : box.high.x, p.y >= 0 ? box.low.y : box.high.y,
                             p.z >= 0 ? box.low.z : box.high.z);
    const double reach = std::abs(p.x * nearest.x) + std::abs(p.y * nearest.y) +
                         std::abs(p.z * nearest.z) + std::abs(p.w);
    if (glm::dot(glm::dvec3(p), nearest) - p.w > 1e-9 * reach)
      return true;
  }
  return false;
}

double distance_to(const Box& box) {  // from the camera, at the origin
  const glm::dvec3 nearest = glm::clamp(glm::dvec3(0.0), box.low, box.high);
  return glm::length(nearest);
}

struct Culler {
  const GeoMipMap& map;
  const View& view;
  Selection& out;

  void visit(int depth, int x, int z) {
    const auto [w, h] = map.quadtree_size[static_cast<std::size_t>(depth)];
    if (x >= w || z >= h)
      return;
    const GeoMipMap::Node& node =
        map.quadtree[static_cast<std::size_t>(depth)][static_cast<std::size_t>(z) * w + x];
    const int span = 1 << depth;
    const int tx0 = x * span, tz0 = z * span;
    const int tx1 = std::min(tx0 + span, map.tiles_x), tz1 = std::min(tz0 + span, map.tiles_z);
    ++out.counts.nodes_visited;
    const Box box = tile_box(map, view, tx0, tz0, tx1, tz1, node.low, node.high);
    if (outside(box, view.planes)) {
      ++out.counts.nodes_culled;
      out.counts.tiles_culled += static_cast<std::uint64_t>(tx1 - tx0) * (tz1 - tz0);
      return;
    }
    if (depth > 0) {
      for (int dz = 0; dz < 2; ++dz) {
        for (int dx = 0; dx < 2; ++dx)
          visit(depth - 1, 2 * x + dx, 2 * z + dz);
      }
      return;
    }
    const TileBounds& tile = map.tiles[static_cast<std::size_t>(z) * map.tiles_x + x];
    const double distance = distance_to(box);
    int level = 0;
    if (distance > 0) {
      // error[L] pixels_per_tangent / distance <= tau, as error[L] ppt <= tau distance (no
      // division); error is non-decreasing, so the first level that fails ends the search.
      for (int l = 1; l < map.levels; ++l) {
        if (tile.error[static_cast<std::size_t>(l)] * view.pixels_per_tangent >
            view.pixel_error * distance) {
          break;
        }
        level = l;
      }
    }
    out.level[static_cast<std::size_t>(z) * map.tiles_x + x] = level;
    ++out.counts.tiles_drawn;
    ++out.counts.tiles_per_level[level];
  }
};

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

Selection select_levels(const GeoMipMap& map, const View& view) {
  Selection out;
  out.level.assign(map.tiles.size(), -1);
  Culler culler{map, view, out};
  culler.visit(static_cast<int>(map.quadtree.size()) - 1, 0, 0);
  return out;
}

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
      const int level = level_at(tx, tz);
      if (level < 0)
        continue;
      // Each side at the coarser spacing of the two tiles that share it (a culled neighbour or
      // the field's edge: this tile's own).
      const auto side = [&](int nx, int nz) { return 1 << std::max(level, level_at(nx, nz)); };
      builder.tile(tx, tz, level,
                   {side(tx, tz - 1), side(tx + 1, tz), side(tx, tz + 1), side(tx - 1, tz)});
    }
  }
  return mesh;
}

}  // namespace relief::geomipmap
