// GeoMipMapping per frame (core/heightfield/geomipmap.h): castledragmire's quadtree of AABBs
// culled against the view frustum, each tile's level by de Boer's screen-space error, then
// occlusion culling. In double.
//
// Occlusion culling, and why it never removes a triangle that would show. The occluders are
// the tiles' floors: the rectangle over a tile's footprint at its lowest height, which every
// triangle of the tile lies on or above (they join lattice points of the tile). A ray that
// meets a floor is there at or below the drawn surface. If it started above the surface, it
// crossed it on the way, at a point P no farther than the floor; P lies in some tile W. The
// occlusion buffer keeps, per cell of pixels, the least over the floors that cover the whole
// cell of their farthest view depth (w, along the camera's forward); a tile is occluded when
// every cell its box can cover holds a depth below the box's nearest w by a relative margin
// (1e-3: far above the rounding of a reverse-Z float depth, near / w, whose relative precision
// is the same at every distance; a conventional [-1, 1] depth would need more).
// W is never occluded: the cell of this ray holds a depth at least P's, which is at least W's
// nearest. So every pixel shows a drawn surface nearer than any occluded tile's: removing
// those tiles changes no pixel, the margin keeping their float depths apart.
// It holds when every ray starts above the surface: the rays' points nearer than the near
// plane lie within near * sqrt(1 + tan_x^2 + tan_y^2) of the camera, so the camera must be
// that far inside the extent and that far above the highest tile within it; and when P is in
// the frustum, so each floor must lie between the near and the far plane. Otherwise no tile is
// culled by occlusion.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/frustum_polytope.h"
#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

constexpr double kOcclusionMargin = 1e-3;
constexpr int kMaxOcclusionCell = 4096;

struct Box {
  glm::dvec3 low, high;  // world
};

// The tiles [tx0, tx1) x [tz0, tz1) between the heights low and high.
Box tile_box(const GeoMipMap& map, int tx0, int tz0, int tx1, int tz1, double low, double high) {
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
  return {glm::dvec3(x_at(tx0), low, z_at(tz0)), glm::dvec3(x_at(tx1), high, z_at(tz1))};
}

// Outside one plane with every corner (planes camera-relative): the corner nearest the inside
// is beyond d by more than a relative 1e-9, so rounding never culls a box touching the frustum.
bool outside(const Box& world, const glm::dvec3& camera, const std::vector<glm::dvec4>& planes) {
  const Box box{world.low - camera, world.high - camera};
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

int tile_level(const GeoMipMap& map, const View& view, const TileBounds& tile, const Box& box) {
  const double distance =
      glm::length(glm::clamp(view.camera.position, box.low, box.high) - view.camera.position);
  // tan_half_fov_y > 0 (a field of view in (0, 180) degrees): ppt is finite.
  const double ppt = view.height / (2 * view.camera.tan_half_fov_y);
  int level = 0;
  if (distance > 0) {
    // error[L] ppt / distance <= tau as error[L] ppt <= tau distance (no division); error is
    // non-decreasing, so the first level that fails ends the search.
    for (int l = 1; l < map.levels; ++l) {
      if (tile.error[static_cast<std::size_t>(l)] * ppt > view.pixel_error * distance)
        break;
      level = l;
    }
  }
  return level;
}

struct Culler {
  const GeoMipMap& map;
  const View& view;
  const std::vector<glm::dvec4>& planes;
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
    if (outside(tile_box(map, tx0, tz0, tx1, tz1, node.low, node.high), view.camera.position,
                planes)) {
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
    out.drawn[static_cast<std::size_t>(z) * map.tiles_x + x] = 1;
  }
};

// Lowers levels until every two neighbours differ by at most one: each pass sets a tile to
// at most one above its finest neighbour, in a fixed order, until no level changes; levels
// only decrease, so it ends (after at most levels x tiles changes).
void limit_level_differences(const GeoMipMap& map, std::vector<int>& level) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int tz = 0; tz < map.tiles_z; ++tz) {
      for (int tx = 0; tx < map.tiles_x; ++tx) {
        int& l = level[static_cast<std::size_t>(tz) * map.tiles_x + tx];
        const auto bound = [&](int nx, int nz) {
          if (nx >= 0 && nz >= 0 && nx < map.tiles_x && nz < map.tiles_z) {
            const int n = level[static_cast<std::size_t>(nz) * map.tiles_x + nx];
            if (l > n + 1) {
              l = n + 1;
              changed = true;
            }
          }
        };
        bound(tx - 1, tz);
        bound(tx + 1, tz);
        bound(tx, tz - 1);
        bound(tx, tz + 1);
      }
    }
  }
}

// Window coordinates (pixels, y up) and view depth w of a world point; w > 0 required.
struct Projected {
  double x, y, w;
};
Projected project(const View& view, const glm::dvec3& p) {
  const CameraFrame& c = view.camera;
  const glm::dvec3 d = p - c.position;
  const double w = glm::dot(d, c.forward);
  // w >= near > 0 (checked by the callers before any use): the divisions are safe.
  return {(glm::dot(d, c.right) / (c.tan_half_fov_x * w) + 1) * 0.5 * view.width,
          (glm::dot(d, c.up) / (c.tan_half_fov_y * w) + 1) * 0.5 * view.height, w};
}

// The buffer cell of a window coordinate, clamped to the buffer in double before the cast (a
// point near the camera's plane projects far beyond any int).
int cell_index(double coordinate, int cell, int cells) {
  return static_cast<int>(std::clamp(std::floor(coordinate / cell), 0.0, cells - 1.0));
}

// Whether every ray starts above the surface (the header comment).
bool occlusion_sound(const GeoMipMap& map, const View& view) {
  const CameraFrame& c = view.camera;
  const double reach = c.near * std::sqrt(1 + c.tan_half_fov_x * c.tan_half_fov_x +
                                          c.tan_half_fov_y * c.tan_half_fov_y);
  const glm::dvec3 p = c.position;
  if (!(p.x - reach > map.extent[0] && p.x + reach < map.extent[2] && p.z - reach > map.extent[1] &&
        p.z + reach < map.extent[3])) {
    return false;
  }
  for (int tz = 0; tz < map.tiles_z; ++tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      const TileBounds& t = map.tiles[static_cast<std::size_t>(tz) * map.tiles_x + tx];
      const Box box = tile_box(map, tx, tz, tx + 1, tz + 1, t.low, t.high);
      const bool near_camera = p.x + reach >= box.low.x && p.x - reach <= box.high.x &&
                               p.z + reach >= box.low.z && p.z - reach <= box.high.z;
      if (near_camera && !(p.y - reach > t.high))
        return false;
    }
  }
  return true;
}

void occlusion_cull(const GeoMipMap& map, const View& view, Selection& out) {
  if (!view.occlusion || view.width <= 0 || view.height <= 0 || view.occlusion_cell <= 0 ||
      !occlusion_sound(map, view)) {
    return;
  }
  const int cell = view.occlusion_cell;
  const int cells_x = (view.width + cell - 1) / cell, cells_y = (view.height + cell - 1) / cell;
  std::vector<double> depth(static_cast<std::size_t>(cells_x) * cells_y,
                            std::numeric_limits<double>::infinity());
  const double near = view.camera.near, far = view.camera.far;
  // The floors of the drawn tiles.
  for (std::size_t t = 0; t < map.tiles.size(); ++t) {
    if (!out.drawn[t])
      continue;
    const int tx = static_cast<int>(t % static_cast<std::size_t>(map.tiles_x));
    const int tz = static_cast<int>(t / static_cast<std::size_t>(map.tiles_x));
    const double y = map.tiles[t].low;
    const Box box = tile_box(map, tx, tz, tx + 1, tz + 1, y, y);
    const glm::dvec3 corners[4] = {{box.low.x, y, box.low.z},
                                   {box.high.x, y, box.low.z},
                                   {box.high.x, y, box.high.z},
                                   {box.low.x, y, box.high.z}};
    Projected q[4];
    double far_w = 0, x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    bool usable = true;
    for (int k = 0; k < 4; ++k) {
      const double w = glm::dot(corners[k] - view.camera.position, view.camera.forward);
      if (!(w >= near && w <= far)) {
        usable = false;
        break;
      }
      q[k] = project(view, corners[k]);
      far_w = std::max(far_w, q[k].w);
      x0 = std::min(x0, q[k].x), x1 = std::max(x1, q[k].x);
      y0 = std::min(y0, q[k].y), y1 = std::max(y1, q[k].y);
    }
    if (!usable)
      continue;
    // The projected floor is a convex quadrilateral; a cell counts when its four corners are
    // inside every edge (either winding) by a relative 1e-9.
    double orientation = 0;
    for (int k = 0; k < 4; ++k) {
      const Projected& a = q[k];
      const Projected& b = q[(k + 1) % 4];
      orientation += a.x * b.y - b.x * a.y;
    }
    if (orientation == 0)
      continue;  // seen edge on
    const double sign = orientation > 0 ? 1 : -1;
    const auto inside = [&](double px, double py) {
      for (int k = 0; k < 4; ++k) {
        const Projected& a = q[k];
        const Projected& b = q[(k + 1) % 4];
        const double cross = ((b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x)) * sign;
        const double scale =
            (std::abs(b.x - a.x) + std::abs(b.y - a.y)) * (std::abs(px) + std::abs(py) + 1);
        if (!(cross > 1e-9 * scale))
          return false;
      }
      return true;
    };
    const int cx0 = cell_index(x0, cell, cells_x), cx1 = cell_index(x1, cell, cells_x);
    const int cy0 = cell_index(y0, cell, cells_y), cy1 = cell_index(y1, cell, cells_y);
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) {
        const double ax = cx * cell, bx = std::min((cx + 1) * cell, view.width);
        const double ay = cy * cell, by = std::min((cy + 1) * cell, view.height);
        if (inside(ax, ay) && inside(bx, ay) && inside(bx, by) && inside(ax, by)) {
          double& d = depth[static_cast<std::size_t>(cy) * cells_x + cx];
          if (std::isinf(d))
            ++out.counts.occlusion_cells;
          d = std::min(d, far_w);
        }
      }
    }
  }
  // The drawn tiles' boxes against the buffer. Every decision reads the buffer of all floors,
  // so it does not depend on the order of the tiles.
  std::vector<std::uint8_t> occluded(map.tiles.size(), 0);
  for (std::size_t t = 0; t < map.tiles.size(); ++t) {
    if (!out.drawn[t])
      continue;
    const int tx = static_cast<int>(t % static_cast<std::size_t>(map.tiles_x));
    const int tz = static_cast<int>(t / static_cast<std::size_t>(map.tiles_x));
    const Box box = tile_box(map, tx, tz, tx + 1, tz + 1, map.tiles[t].low, map.tiles[t].high);
    double nearest = HUGE_VAL, x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    bool in_front = true;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p((k & 1) ? box.high.x : box.low.x, (k & 2) ? box.high.y : box.low.y,
                         (k & 4) ? box.high.z : box.low.z);
      if (!(glm::dot(p - view.camera.position, view.camera.forward) >= near)) {
        in_front = false;
        break;
      }
      const Projected q = project(view, p);
      nearest = std::min(nearest, q.w);
      x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
      y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    }
    if (!in_front)
      continue;
    const int cx0 = cell_index(x0, cell, cells_x), cx1 = cell_index(x1, cell, cells_x);
    const int cy0 = cell_index(y0, cell, cells_y), cy1 = cell_index(y1, cell, cells_y);
    if (cx0 > cx1 || cy0 > cy1)
      continue;  // off screen: the frustum test keeps it
    bool hidden = true;
    for (int cy = cy0; cy <= cy1 && hidden; ++cy) {
      for (int cx = cx0; cx <= cx1 && hidden; ++cx) {
        hidden =
            depth[static_cast<std::size_t>(cy) * cells_x + cx] * (1 + kOcclusionMargin) < nearest;
      }
    }
    occluded[t] = hidden ? 1 : 0;
  }
  for (std::size_t t = 0; t < map.tiles.size(); ++t) {
    if (occluded[t]) {
      out.drawn[t] = 0;
      ++out.counts.tiles_occluded;
    }
  }
  out.occluded = std::move(occluded);  // the mesh's stable triangle numbers count them
}

}  // namespace

Selection select_levels(const GeoMipMap& map, const View& view) {
  if (map.tiles.empty() || map.quadtree.empty()) {
    throw std::invalid_argument("GeoMipMap without tiles: build it with build_geomipmap");
  }
  if (view.width <= 0 || view.height <= 0 || !(view.pixel_error >= 0) ||
      !std::isfinite(view.pixel_error) || view.occlusion_cell < 1 ||
      view.occlusion_cell > kMaxOcclusionCell) {
    throw std::invalid_argument(
        "view " + std::to_string(view.width) + " x " + std::to_string(view.height) +
        " pixels, tau " + std::to_string(view.pixel_error) + ", occlusion cell " +
        std::to_string(view.occlusion_cell) +
        "; allowed positive sizes, a finite tau >= 0 and a cell of 1 ... 4096 pixels");
  }
  const CameraFrame& c = view.camera;
  if (!(c.near > 0 && c.far > c.near && c.tan_half_fov_x > 0 && c.tan_half_fov_y > 0 &&
        std::isfinite(c.far) && std::isfinite(c.tan_half_fov_x) &&
        std::isfinite(c.tan_half_fov_y))) {
    // The projections divide by w >= near and by the tangents.
    throw std::invalid_argument("view camera: near " + std::to_string(c.near) + ", far " +
                                std::to_string(c.far) +
                                "; allowed 0 < near < far, finite, and a field of view in "
                                "(0, 180) degrees");
  }
  // A NaN position would fail every comparison: nothing culled, level 0 everywhere, silently.
  if (!(std::isfinite(c.position.x) && std::isfinite(c.position.y) &&
        std::isfinite(c.position.z))) {
    throw std::invalid_argument("view camera position: not finite");
  }
  Selection out;
  out.level.assign(map.tiles.size(), 0);
  out.drawn.assign(map.tiles.size(), 0);
  const std::vector<glm::dvec4> planes = frustum_polytope(view.camera).planes;
  Culler culler{map, view, planes, out};
  culler.visit(static_cast<int>(map.quadtree.size()) - 1, 0, 0);
  for (int tz = 0; tz < map.tiles_z; ++tz) {
    for (int tx = 0; tx < map.tiles_x; ++tx) {
      const std::size_t t = static_cast<std::size_t>(tz) * map.tiles_x + tx;
      const TileBounds& tile = map.tiles[t];
      out.level[t] =
          tile_level(map, view, tile, tile_box(map, tx, tz, tx + 1, tz + 1, tile.low, tile.high));
    }
  }
  limit_level_differences(map, out.level);
  occlusion_cull(map, view, out);
  for (std::size_t t = 0; t < map.tiles.size(); ++t) {
    if (!out.drawn[t])
      continue;
    ++out.counts.tiles_drawn;
    ++out.counts.tiles_per_level[out.level[t]];
  }
  return out;
}

}  // namespace relief::geomipmap
