// Triangle sources for the rasteriser: an explicit index list, or the projected grid's
// implicit topology. Both give triangle t's three vertex indices in GL's order, and whether
// the triangle is drawn at all. The primitive id of triangle t is t, as gl_PrimitiveID is for
// glDrawElements(GL_TRIANGLES, ...).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/grid_buffers.h"

namespace relief::raster {

struct IndexedTriangles {
  std::span<const std::uint32_t> indices;  // 3 per triangle

  std::uint32_t count() const { return static_cast<std::uint32_t>(indices.size() / 3); }
  bool vertices(std::uint32_t t, std::uint32_t v[3]) const {
    v[0] = indices[3 * t];
    v[1] = indices[3 * t + 1];
    v[2] = indices[3 * t + 2];
    return true;
  }
};

// Two triangles per grid cell. Cell (i, j) has corners a = (i, j), b = (i+1, j),
// c = (i+1, j+1), d = (i, j+1); its triangles are (a, b, c) = 2 cell and (a, c, d) = 2 cell + 1,
// cell = j (width - 1) + i: the diagonal always runs from (i, j) to (i+1, j+1). Grid i runs
// with the camera's right and j away from it, so both are counter-clockwise seen from above.
// A cell with any invalid corner is skipped (both triangles).
struct GridTriangles {
  GridLayout layout;
  std::span<const std::uint8_t> valid;
  // VertexNeed flags (core/vertex_culling.h): a triangle is drawn only if its three vertices
  // have kDraw (bit 2); empty: no such condition.
  std::span<const std::uint8_t> need = {};

  std::uint32_t count() const {
    return 2u * static_cast<std::uint32_t>(layout.width - 1) *
           static_cast<std::uint32_t>(layout.height - 1);
  }
  bool vertices(std::uint32_t t, std::uint32_t v[3]) const {
    const std::uint32_t cell = t >> 1;
    const int i = static_cast<int>(cell % static_cast<std::uint32_t>(layout.width - 1));
    const int j = static_cast<int>(cell / static_cast<std::uint32_t>(layout.width - 1));
    const auto a = static_cast<std::uint32_t>(layout.index(i, j));
    const auto b = static_cast<std::uint32_t>(layout.index(i + 1, j));
    const auto c = static_cast<std::uint32_t>(layout.index(i + 1, j + 1));
    const auto d = static_cast<std::uint32_t>(layout.index(i, j + 1));
    v[0] = a;
    v[1] = (t & 1) ? c : b;
    v[2] = (t & 1) ? d : c;
    return valid[a] && valid[b] && valid[c] && valid[d] &&
           (need.empty() || (need[v[0]] & need[v[1]] & need[v[2]] & 2u) != 0);
  }
  // Vertex indices [first, last) that hold every vertex of triangles [begin, end)
  // (begin < end <= count()): from corner a of the first one's cell to corner c of the last
  // one's (vertex indices grow with the cell).
  struct VertexSpan {
    std::size_t first, last;
  };
  VertexSpan vertex_span(std::uint32_t begin, std::uint32_t end) const {
    const auto columns = static_cast<std::uint32_t>(layout.width - 1);
    const std::uint32_t first_cell = begin >> 1, last_cell = (end - 1) >> 1;
    return {layout.index(static_cast<int>(first_cell % columns),
                         static_cast<int>(first_cell / columns)),
            layout.index(static_cast<int>(last_cell % columns) + 1,
                         static_cast<int>(last_cell / columns) + 1) +
                1};
  }
};

// The frame's triangles as the tile pass reads them: the projected grid's implicit topology,
// or an index list (a height field's GeoMipMap mesh, core/heightfield/field_mesh.h).
class FrameTriangles {
 public:
  FrameTriangles(const GridTriangles& grid) : grid_(grid) {}  // NOLINT: either source converts
  FrameTriangles(const IndexedTriangles& indexed)             // NOLINT
      : indexed_(indexed), is_indexed_(true) {}

  std::uint32_t count() const { return is_indexed_ ? indexed_.count() : grid_.count(); }
  bool vertices(std::uint32_t t, std::uint32_t v[3]) const {
    return is_indexed_ ? indexed_.vertices(t, v) : grid_.vertices(t, v);
  }

 private:
  GridTriangles grid_;
  IndexedTriangles indexed_;
  bool is_indexed_ = false;
};

}  // namespace relief::raster
