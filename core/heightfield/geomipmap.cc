#include "core/heightfield/geomipmap.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/heightfield/geomipmap_triangles.h"

namespace relief::geomipmap {
namespace {

constexpr int kMaxTileCells = 256;

// (b - a) x (p - a) in (u, v), its y as for emit_counter_clockwise: positive when p is to the
// left of a -> b seen from +y.
long long orient(LatticeStep a, LatticeStep b, LatticeStep p) {
  return static_cast<long long>(b[1] - a[1]) * (p[0] - a[0]) -
         static_cast<long long>(b[0] - a[0]) * (p[1] - a[1]);
}

// The largest |height - the triangle's plane| over the lattice points in the triangle (a, b,
// c), counter-clockwise, of the tile whose first lattice point is (c0, r0).
double triangle_error(const FieldLattice& f, int c0, int r0, LatticeStep a, LatticeStep b,
                      LatticeStep c) {
  const auto h = [&](LatticeStep p) {
    return static_cast<double>(
        f.heights[static_cast<std::size_t>(r0 + p[1]) * f.columns + (c0 + p[0])]);
  };
  const long long area = orient(a, b, c);  // > 0: the generator emits no degenerate triangle
  const double ha = h(a), hb = h(b), hc = h(c);
  double worst = 0;
  for (int v = std::min({a[1], b[1], c[1]}); v <= std::max({a[1], b[1], c[1]}); ++v) {
    for (int u = std::min({a[0], b[0], c[0]}); u <= std::max({a[0], b[0], c[0]}); ++u) {
      const LatticeStep p{u, v};
      const long long wa = orient(b, c, p), wb = orient(c, a, p), wc = orient(a, b, p);
      if (wa < 0 || wb < 0 || wc < 0)
        continue;
      const double plane = (static_cast<double>(wa) * ha + static_cast<double>(wb) * hb +
                            static_cast<double>(wc) * hc) /
                           static_cast<double>(area);
      worst = std::max(worst, std::abs(h(p) - plane));
    }
  }
  return worst;
}

// The level's error: over every triangle the tile can draw at spacing s, its interior and each
// side's trapezoid at the spacings a neighbour can give it: s, or 2s from a neighbour one level
// coarser (select_levels keeps neighbours within one level, as GeoMipMapping implementations
// commonly do; at every spacing up to T the border's worst case made every level's error that
// of the coarsest, and level 0 was chosen everywhere).
double level_error(const FieldLattice& f, int c0, int r0, int tile_cells, int s) {
  double worst = 0;
  const auto measure = [&](LatticeStep a, LatticeStep b, LatticeStep c) {
    worst = std::max(worst, triangle_error(f, c0, r0, a, b, c));
  };
  if (s == tile_cells) {
    tile_triangles(tile_cells, s, {s, s, s, s}, measure);
    return worst;
  }
  interior_triangles(tile_cells, s, measure);
  for (int side = 0; side < 4; ++side) {
    for (int edge = s; edge <= std::min(2 * s, tile_cells); edge *= 2)
      side_triangles(tile_cells, s, side, edge, measure);
  }
  return worst;
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

GeoMipMap build_geomipmap(const FieldLattice& f, int tile_cells, const ParallelRows& parallel) {
  if (!valid_tile_cells(tile_cells)) {
    throw std::invalid_argument("tile cells = " + std::to_string(tile_cells) +
                                "; allowed a power of two in [2, 256]");
  }
  if (f.columns < 2 || f.rows < 2 || f.columns > kMaxLatticeSide || f.rows > kMaxLatticeSide ||
      (f.columns - 1) % tile_cells != 0 || (f.rows - 1) % tile_cells != 0) {
    throw std::invalid_argument(
        "lattice " + std::to_string(f.columns) + " x " + std::to_string(f.rows) + "; allowed k " +
        std::to_string(tile_cells) + " + 1 vertices a side, k >= 1, at most " +
        std::to_string(kMaxLatticeSide));
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
  // Checked here, in order, so that the message names the first whichever row runs first.
  const auto not_finite =
      std::find_if(f.heights.begin(), f.heights.end(), [](float h) { return !std::isfinite(h); });
  if (not_finite != f.heights.end()) {
    const auto at = static_cast<std::size_t>(not_finite - f.heights.begin());
    throw std::invalid_argument("lattice height at column " + std::to_string(at % f.columns) +
                                ", row " + std::to_string(at / f.columns) + ": not finite");
  }
  // The spans too: an extent from -1.5e308 to 1.5e308 has finite ends and no finite width.
  if (!(f.extent[2] > f.extent[0] && f.extent[3] > f.extent[1] &&
        std::isfinite(f.extent[2] - f.extent[0]) && std::isfinite(f.extent[3] - f.extent[1]))) {
    throw std::invalid_argument("lattice extent: x1 > x0 and z1 > z0, finite spans, required");
  }
  GeoMipMap map;
  map.tile_cells = tile_cells;
  map.levels = std::countr_zero(static_cast<unsigned>(tile_cells)) + 1;  // T: a power of two
  map.tiles_x = (f.columns - 1) / tile_cells;
  map.tiles_z = (f.rows - 1) / tile_cells;
  map.extent = f.extent;
  map.tiles.resize(static_cast<std::size_t>(map.tiles_x) * map.tiles_z);
  run_rows(parallel, map.tiles_z, [&](int tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      TileBounds& t = map.tiles[static_cast<std::size_t>(tz) * map.tiles_x + tx];
      const int c0 = tx * tile_cells, r0 = tz * tile_cells;
      float low = std::numeric_limits<float>::infinity(), high = -low;
      for (int v = 0; v <= tile_cells; ++v) {
        for (int u = 0; u <= tile_cells; ++u) {
          const float h = f.heights[static_cast<std::size_t>(r0 + v) * f.columns + (c0 + u)];
          low = std::min(low, h);
          high = std::max(high, h);
        }
      }
      t.low = low;
      t.high = high;
      // Level 0 keeps every vertex, but a coarser neighbour still widens its border's steps.
      t.error.assign(static_cast<std::size_t>(map.levels), 0.0);
      t.error[0] = level_error(f, c0, r0, tile_cells, 1);
      for (int level = 1; level < map.levels; ++level) {
        // Non-decreasing with the level (de Boer), so the level search may stop at the first
        // level that fails.
        const double worst =
            std::max(t.error[level - 1], level_error(f, c0, r0, tile_cells, 1 << level));
        t.error[level] = worst;
      }
    }
  });
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
