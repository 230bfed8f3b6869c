#include "core/vertex_culling.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace relief {

namespace {

// All five planes outside: what an invalid vertex gets, so that it never makes a triangle
// look visible (its cells are not drawn anyway).
constexpr std::uint8_t kAllOutside = 0x1f;

}  // namespace

template <class Real>
CullParams<Real> make_cull_params(const FramePlan& plan) {
  const CameraFrame& c = plan.camera;
  // Inward normals: inside the frustum |p . right| <= tan_x (p . forward) and likewise for up.
  const glm::dvec3 normals[5] = {
      c.tan_half_fov_x * c.forward + c.right, c.tan_half_fov_x * c.forward - c.right,
      c.tan_half_fov_y * c.forward + c.up, c.tan_half_fov_y * c.forward - c.up, c.forward};
  CullParams<Real> p;
  for (int k = 0; k < 5; ++k) {
    p.plane[k][0] = Real(normals[k].x);
    p.plane[k][1] = Real(normals[k].y);
    p.plane[k][2] = Real(normals[k].z);
  }
  p.near = Real(c.near);
  p.height_lo = Real(plan.bounds.world_min - c.position.y);
  p.height_hi = Real(plan.bounds.world_max - c.position.y);
  // 1e-4 of the distance is 1000 float ulps: what the rasteriser computes from the same point
  // in float cannot land on the other side of a plane.
  p.tolerance = Real(1e-4);
  p.width = plan.layout.width;
  p.height = plan.layout.height;
  p.pitch = plan.layout.pitch;
  return p;
}

template <class Real>
void vertex_outcodes(const CullParams<Real>& p, RowRange rows, std::span<const Real> dx,
                     std::span<const Real> dz, std::span<const Real> height,
                     std::span<const std::uint8_t> valid, std::span<std::uint8_t> outcode) {
  const bool bounds = height.empty();
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < p.pitch; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * p.pitch + i;
      if (i >= p.width || !valid[k]) {
        outcode[k] = kAllOutside;
        continue;
      }
      const Real x = dx[k], z = dz[k];
      // The segment (x, h, z), h in [lo, hi]: a plane's value is linear in h, so the segment
      // is outside when both ends are (a point: lo = hi).
      const Real h_lo = bounds ? p.height_lo : height[k];
      const Real h_hi = bounds ? p.height_hi : height[k];
      const Real margin = p.tolerance * (std::abs(x) + std::abs(z) +
                                         std::max(std::abs(h_lo), std::abs(h_hi)) + p.near);
      std::uint8_t code = 0;
      for (int plane = 0; plane < 5; ++plane) {
        const Real* n = p.plane[plane];
        const Real offset = plane == 4 ? p.near : Real(0);
        const Real flat = n[0] * x + n[2] * z - offset;
        const Real lo = flat + n[1] * h_lo;
        const Real hi = flat + n[1] * h_hi;
        if (std::max(lo, hi) < -margin) {
          code = static_cast<std::uint8_t>(code | (1u << plane));
        }
      }
      outcode[k] = code;
    }
  }
}

namespace {

// Which triangles of the cells around rows [rows.begin, rows.end) may be visible, from the
// outcodes: a triangle may be visible when its cell is drawn (four valid corners) and its
// three vertices share no outside plane.
class VisibleTriangles {
 public:
  VisibleTriangles(const GridLayout& layout, RowRange rows, std::span<const std::uint8_t> valid,
                   std::span<const std::uint8_t> outcode)
      : layout_(layout),
        // Cell rows rows.begin - 2 .. rows.end (clamped): a vertex's triangles reach one row
        // around it, a normal one more.
        cell_lo_(std::max(0, rows.begin - 2)),
        cell_hi_(std::min(layout.height - 2, rows.end)),
        cells_(static_cast<std::size_t>(std::max(0, cell_hi_ - cell_lo_ + 1)) * layout.width, 0) {
    const int w = layout.width;
    const auto code = [&](int i, int j) { return outcode[layout.index(i, j)]; };
    for (int cj = cell_lo_; cj <= cell_hi_; ++cj) {
      for (int ci = 0; ci + 1 < w; ++ci) {
        const std::size_t a = layout.index(ci, cj), b = layout.index(ci + 1, cj);
        const std::size_t c = layout.index(ci + 1, cj + 1), d = layout.index(ci, cj + 1);
        if (!(valid[a] && valid[b] && valid[c] && valid[d])) {
          continue;
        }
        // Bit 0: triangle (a, b, c) of the cell; bit 1: (a, c, d) (topology.h).
        const std::uint8_t lower = code(ci, cj) & code(ci + 1, cj) & code(ci + 1, cj + 1);
        const std::uint8_t upper = code(ci, cj) & code(ci + 1, cj + 1) & code(ci, cj + 1);
        cells_[static_cast<std::size_t>(cj - cell_lo_) * w + ci] =
            static_cast<std::uint8_t>((lower == 0 ? 1 : 0) | (upper == 0 ? 2 : 0));
      }
    }
  }

  // Whether a triangle around vertex (i, j) may be visible: the vertex is a of cell (i, j), b
  // of (i - 1, j), c of (i - 1, j - 1) and d of (i, j - 1).
  bool draws(int i, int j) const {
    if (i < 0 || j < 0 || i >= layout_.width || j >= layout_.height) {
      return false;
    }
    return cell(i, j) != 0 || (cell(i - 1, j) & 1) != 0 || cell(i - 1, j - 1) != 0 ||
           (cell(i, j - 1) & 2) != 0;
  }

 private:
  std::uint8_t cell(int ci, int cj) const {
    if (ci < 0 || cj < 0 || ci >= layout_.width - 1 || cj < cell_lo_ || cj > cell_hi_) {
      return 0;
    }
    return cells_[static_cast<std::size_t>(cj - cell_lo_) * layout_.width + ci];
  }

  GridLayout layout_;
  int cell_lo_, cell_hi_;
  std::vector<std::uint8_t> cells_;
};

void add_flags(std::uint8_t flags, bool valid, NeedCount& count) {
  count.evaluate += (flags & kEvaluate) != 0;
  count.draw += (flags & kDraw) != 0;
  count.valid_draw += (flags & kDraw) != 0 && valid;
}

}  // namespace

NeedCount vertex_needs(const GridLayout& layout, RowRange rows, std::span<const std::uint8_t> valid,
                       std::span<const std::uint8_t> outcode, std::span<std::uint8_t> need) {
  const VisibleTriangles visible(layout, rows, valid, outcode);
  NeedCount count;
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < layout.pitch; ++i) {
      const std::size_t k = layout.index(i, j);
      std::uint8_t flags = 0;
      if (i < layout.width && valid[k]) {
        if (visible.draws(i, j)) {
          flags = kDraw | kEvaluate;
        } else if (visible.draws(i - 1, j) || visible.draws(i + 1, j) || visible.draws(i, j - 1) ||
                   visible.draws(i, j + 1)) {
          flags = kEvaluate;
        }
      }
      need[k] = flags;
      add_flags(flags, valid[k] != 0, count);
    }
  }
  return count;
}

NeedCount refine_draw_needs(const GridLayout& layout, RowRange rows,
                            std::span<const std::uint8_t> valid,
                            std::span<const std::uint8_t> outcode, std::span<std::uint8_t> need) {
  const VisibleTriangles visible(layout, rows, valid, outcode);
  NeedCount count;
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < layout.pitch; ++i) {
      const std::size_t k = layout.index(i, j);
      std::uint8_t flags = need[k] & kEvaluate;
      if ((need[k] & kDraw) && i < layout.width && valid[k] && visible.draws(i, j)) {
        flags |= kDraw;
      }
      need[k] = flags;
      add_flags(flags, valid[k] != 0, count);
    }
  }
  return count;
}

NeedCount count_needs(const GridLayout& layout, RowRange rows, std::span<const std::uint8_t> valid,
                      std::span<const std::uint8_t> need) {
  NeedCount count;
  for (std::size_t k = layout.index(0, rows.begin); k < layout.index(0, rows.end); ++k) {
    add_flags(need[k], valid[k] != 0, count);
  }
  return count;
}

NeedCount vertex_needs_without_culling(const GridLayout& layout, RowRange rows,
                                       std::span<const std::uint8_t> valid, bool include_invalid,
                                       std::span<std::uint8_t> need) {
  NeedCount count;
  for (std::size_t k = layout.index(0, rows.begin); k < layout.index(0, rows.end); ++k) {
    const bool needed = include_invalid || valid[k] != 0;
    const std::uint8_t flags = needed ? (kEvaluate | kDraw) : 0;
    need[k] = flags;
    add_flags(flags, valid[k] != 0, count);
  }
  return count;
}

template CullParams<float> make_cull_params<float>(const FramePlan&);
template CullParams<double> make_cull_params<double>(const FramePlan&);
template void vertex_outcodes<float>(const CullParams<float>&, RowRange, std::span<const float>,
                                     std::span<const float>, std::span<const float>,
                                     std::span<const std::uint8_t>, std::span<std::uint8_t>);
template void vertex_outcodes<double>(const CullParams<double>&, RowRange, std::span<const double>,
                                      std::span<const double>, std::span<const double>,
                                      std::span<const std::uint8_t>, std::span<std::uint8_t>);

}  // namespace relief
