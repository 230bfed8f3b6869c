#include "core/heightfield/geomipmap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace relief::geomipmap {
namespace {

constexpr int kMaxTileCells = 256;

int log2_exact(int n) {
  int k = 0;
  while ((1 << k) < n)
    ++k;
  return k;
}

// The regular level-L triangulation of a tile (cells of s = 2^L lattice steps, each split by
// the diagonal from its (0, 0) to its (s, s) corner) at the lattice point (u, v) of the tile,
// tile-local steps in [0, T]: de Boer's estimate of the level's surface.
double level_surface(const FieldLattice& f, int c0, int r0, int s, int tile_cells, int u, int v) {
  // The cell holding (u, v): a point on the tile's far edge belongs to the last cell (values
  // on a cell's edge are the same from either side: linear along it).
  const int ua = std::min(u / s, tile_cells / s - 1) * s;
  const int vb = std::min(v / s, tile_cells / s - 1) * s;
  const auto h = [&](int du, int dv) {
    return static_cast<double>(
        f.heights[static_cast<std::size_t>(r0 + dv) * f.columns + (c0 + du)]);
  };
  const double fu = static_cast<double>(u - ua) / s;  // s >= 2: in [0, 1]
  const double fv = static_cast<double>(v - vb) / s;
  const double h00 = h(ua, vb), h10 = h(ua + s, vb);
  const double h01 = h(ua, vb + s), h11 = h(ua + s, vb + s);
  return fu >= fv ? h00 + fu * (h10 - h00) + fv * (h11 - h10)
                  : h00 + fv * (h01 - h00) + fu * (h11 - h01);
}

}  // namespace

glm::dvec2 FieldLattice::position(int column, int row) const {
  // columns, rows >= 2 (build_geomipmap): the divisions are by at least 1.
  const double fx = static_cast<double>(column) / (columns - 1);
  const double fz = static_cast<double>(row) / (rows - 1);
  return {extent[0] + (extent[2] - extent[0]) * fx, extent[1] + (extent[3] - extent[1]) * fz};
}

bool valid_tile_cells(int tile_cells) {
  return tile_cells >= 2 && tile_cells <= kMaxTileCells && (tile_cells & (tile_cells - 1)) == 0;
}

GeoMipMap build_geomipmap(const FieldLattice& f, int tile_cells) {
  if (!valid_tile_cells(tile_cells)) {
    throw std::invalid_argument("tile cells = " + std::to_string(tile_cells) +
                                "; allowed a power of two in [2, 256]");
  }
  if (f.columns < 2 || f.rows < 2 || (f.columns - 1) % tile_cells != 0 ||
      (f.rows - 1) % tile_cells != 0) {
    throw std::invalid_argument("lattice " + std::to_string(f.columns) + " x " +
                                std::to_string(f.rows) + "; allowed k " +
                                std::to_string(tile_cells) + " + 1 vertices a side, k >= 1");
  }
  if (f.heights.size() != static_cast<std::size_t>(f.columns) * f.rows) {
    throw std::invalid_argument("lattice heights: " + std::to_string(f.heights.size()) +
                                " values for " + std::to_string(f.columns) + " x " +
                                std::to_string(f.rows) + " vertices");
  }
  for (const double e : f.extent) {
    if (!std::isfinite(e))
      throw std::invalid_argument("lattice extent: not finite");
  }
  if (!(f.extent[2] > f.extent[0] && f.extent[3] > f.extent[1])) {
    throw std::invalid_argument("lattice extent: x1 > x0 and z1 > z0 required");
  }
  GeoMipMap map;
  map.tile_cells = tile_cells;
  map.levels = log2_exact(tile_cells) + 1;
  map.tiles_x = (f.columns - 1) / tile_cells;
  map.tiles_z = (f.rows - 1) / tile_cells;
  map.extent = f.extent;
  map.tiles.resize(static_cast<std::size_t>(map.tiles_x) * map.tiles_z);
  for (int tz = 0; tz < map.tiles_z; ++tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      TileBounds& t = map.tiles[static_cast<std::size_t>(tz) * map.tiles_x + tx];
      const int c0 = tx * tile_cells, r0 = tz * tile_cells;
      float low = std::numeric_limits<float>::infinity(), high = -low;
      for (int v = 0; v <= tile_cells; ++v) {
        for (int u = 0; u <= tile_cells; ++u) {
          const float h = f.heights[static_cast<std::size_t>(r0 + v) * f.columns + (c0 + u)];
          if (!std::isfinite(h)) {
            throw std::invalid_argument("lattice height at column " + std::to_string(c0 + u) +
                                        ", row " + std::to_string(r0 + v) + ": not finite");
          }
          low = std::min(low, h);
          high = std::max(high, h);
        }
      }
      t.low = low;
      t.high = high;
      t.error.assign(static_cast<std::size_t>(map.levels), 0.0);
      for (int level = 1; level < map.levels; ++level) {
        const int s = 1 << level;
        double worst = t.error[level - 1];  // non-decreasing with the level (de Boer)
        for (int v = 0; v <= tile_cells; ++v) {
          for (int u = 0; u <= tile_cells; ++u) {
            if (u % s == 0 && v % s == 0)
              continue;  // the level keeps this vertex
            const double exact = f.heights[static_cast<std::size_t>(r0 + v) * f.columns + (c0 + u)];
            worst =
                std::max(worst, std::abs(exact - level_surface(f, c0, r0, s, tile_cells, u, v)));
          }
        }
        t.error[level] = worst;
      }
    }
  }
  // The quadtree of height ranges, bottom up.
  map.quadtree.emplace_back();
  map.quadtree_size.push_back({map.tiles_x, map.tiles_z});
  for (const TileBounds& t : map.tiles)
    map.quadtree[0].push_back({t.low, t.high});
  while (map.quadtree_size.back()[0] > 1 || map.quadtree_size.back()[1] > 1) {
    const auto [w, h] = map.quadtree_size.back();
    const int nw = (w + 1) / 2, nh = (h + 1) / 2;
    std::vector<GeoMipMap::Node> next;
    next.reserve(static_cast<std::size_t>(nw) * nh);
    const std::vector<GeoMipMap::Node>& below = map.quadtree.back();
    for (int z = 0; z < nh; ++z) {
      for (int x = 0; x < nw; ++x) {
        GeoMipMap::Node n{std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity()};
        for (int dz = 0; dz < 2; ++dz) {
          for (int dx = 0; dx < 2; ++dx) {
            const int cx = 2 * x + dx, cz = 2 * z + dz;
            if (cx >= w || cz >= h)
              continue;
            const GeoMipMap::Node& c = below[static_cast<std::size_t>(cz) * w + cx];
            n.low = std::min(n.low, c.low);
            n.high = std::max(n.high, c.high);
          }
        }
        next.push_back(n);
      }
    }
    map.quadtree.push_back(std::move(next));
    map.quadtree_size.push_back({nw, nh});
  }
  return map;
}

}  // namespace relief::geomipmap
