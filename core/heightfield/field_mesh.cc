#include "core/heightfield/field_mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/limits.h"

namespace relief {

namespace {

// The B-spline's weights at a knot: (1, 4, 1) / 6 (core/height_sketch.h).
constexpr double kKnotWeight[3] = {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};

struct Texels {
  const float* values;
  int width, height;

  double at(int i, int j) const {  // edge texels extended (GL_CLAMP_TO_EDGE)
    i = std::clamp(i, 0, width - 1);
    j = std::clamp(j, 0, height - 1);
    return values[static_cast<std::size_t>(j) * width + i];
  }
};

Texels texels_of(const HeightSketch& field) {
  return {field.heights.data(), field.width, field.height};
}

int whole_tiles(int texels, int tile_cells) {
  // texels >= 2: at least one tile.
  return (texels - 2) / tile_cells + 1;
}

}  // namespace

std::uintmax_t field_mesh_vertices(int width, int height, int tile_cells) {
  const auto side = [&](int texels) {
    return std::uintmax_t(whole_tiles(texels, tile_cells)) * tile_cells + 1;
  };
  return side(width) * side(height);
}

FieldMesh build_field_mesh(const HeightSketch& field, const std::array<double, 4>& extent,
                           int tile_cells, const ParallelRows& parallel) {
  if (!geomipmap::valid_tile_cells(tile_cells)) {
    throw std::invalid_argument("terrain.heightfield.geomipmap.tile_cells = " +
                                std::to_string(tile_cells) + " is not a power of two in 2..256");
  }
  if (field.width < 2 || field.height < 2) {
    throw std::invalid_argument("terrain.heightfield: a field of " + std::to_string(field.width) +
                                " x " + std::to_string(field.height) +
                                " samples; GeoMipMapping needs at least 2 a side");
  }
  FieldMesh mesh;
  mesh.columns = whole_tiles(field.width, tile_cells) * tile_cells + 1;
  mesh.rows = whole_tiles(field.height, tile_cells) * tile_cells + 1;
  // Texel centres: the extent has sides of at least kMinSketchSpan, so the cells are positive.
  mesh.cell_x = (extent[2] - extent[0]) / field.width;
  mesh.cell_z = (extent[3] - extent[1]) / field.height;
  mesh.extent = {extent[0] + 0.5 * mesh.cell_x, extent[1] + 0.5 * mesh.cell_z,
                 extent[0] + (mesh.columns - 0.5) * mesh.cell_x,
                 extent[1] + (mesh.rows - 0.5) * mesh.cell_z};
  const Texels t = texels_of(field);
  mesh.heights.resize(std::size_t(mesh.columns) * mesh.rows);
  run_rows(parallel, mesh.rows, [&](int r) {
    for (int c = 0; c < mesh.columns; ++c) {
      double sum = 0;
      for (int b = -1; b <= 1; ++b) {
        double row = 0;
        for (int a = -1; a <= 1; ++a) {
          row += kKnotWeight[a + 1] * t.at(c + a, r + b);
        }
        sum += kKnotWeight[b + 1] * row;
      }
      mesh.heights[std::size_t(r) * mesh.columns + c] = static_cast<float>(sum);
    }
  });
  mesh.map = geomipmap::build_geomipmap(mesh.lattice(), tile_cells, parallel);
  return mesh;
}

GridLayout mesh_layout(std::size_t vertices) {
  const std::size_t rows =
      std::max<std::size_t>(1, (vertices + kMeshRowVertices - 1) / kMeshRowVertices);
  return make_grid_layout(kMeshRowVertices, static_cast<int>(rows));
}

template <class Real>
void mesh_domain(const FieldMesh& field, const geomipmap::Mesh& mesh, const glm::dvec3& camera,
                 IndexRange range, DomainSpans<Real> out) {
  const geomipmap::FieldLattice lattice = field.lattice();
  const std::size_t vertices = mesh.vertex_column.size();
  const auto spacing = static_cast<Real>(std::max(field.cell_x, field.cell_z));
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (k < vertices) {
      const glm::dvec2 p = lattice.position(mesh.vertex_column[k], mesh.vertex_row[k]);
      out.dx[k] = static_cast<Real>(p.x - camera.x);
      out.dz[k] = static_cast<Real>(p.y - camera.z);
      out.sigma[k] = spacing;
      out.valid[k] = 1;
    } else {
      out.dx[k] = out.dz[k] = out.sigma[k] = Real(0);
      out.valid[k] = 0;
    }
    out.nu[k] = Real(0);
  }
}

template <class Real>
void mesh_heights(const FieldMesh& field, const geomipmap::Mesh& mesh, double camera_above_base,
                  IndexRange range, std::span<Real> height) {
  const std::size_t vertices = mesh.vertex_column.size();
  for (std::size_t k = range.begin; k < range.end; ++k) {
    height[k] = k < vertices
                    ? static_cast<Real>(
                          double(field.heights[std::size_t(mesh.vertex_row[k]) * field.columns +
                                               mesh.vertex_column[k]]) -
                          camera_above_base)
                    : Real(0);
  }
}

template <class Real>
void mesh_surface(const FieldMesh& field, const HeightSketch& texels, const geomipmap::Mesh& mesh,
                  Real water_level, bool water, IndexRange range, std::span<const Real> height,
                  SurfaceSpans<Real> out) {
  const Texels t = texels_of(texels);
  const std::size_t vertices = mesh.vertex_column.size();
  // cell_x, cell_z > 0 (build_field_mesh): the divisions are defined.
  const double inv_2x = 0.5 / field.cell_x, inv_2z = 0.5 / field.cell_z;
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (k >= vertices) {
      out.nx[k] = out.nz[k] = out.slope[k] = out.water_depth[k] = Real(0);
      out.ny[k] = Real(1);
      continue;
    }
    const int c = mesh.vertex_column[k], r = mesh.vertex_row[k];
    double gx = 0, gz = 0;
    for (int b = -1; b <= 1; ++b) {
      gx += kKnotWeight[b + 1] * (t.at(c + 1, r + b) - t.at(c - 1, r + b));
      gz += kKnotWeight[b + 1] * (t.at(c + b, r + 1) - t.at(c + b, r - 1));
    }
    gx *= inv_2x;
    gz *= inv_2z;
    // |g| is finite (finite texels, positive cells); the length is >= 1.
    const double length = std::sqrt(gx * gx + gz * gz + 1.0);
    out.nx[k] = static_cast<Real>(-gx / length);
    out.ny[k] = static_cast<Real>(1.0 / length);
    out.nz[k] = static_cast<Real>(-gz / length);
    out.slope[k] = static_cast<Real>(std::min(std::sqrt(gx * gx + gz * gz), limits::kMaxSlope));
    out.water_depth[k] =
        water ? std::max(Real(0), static_cast<Real>(water_level - height[k])) : Real(0);
  }
}

#define RELIEF_FIELD_MESH_STAGES(Real)                                                            \
  template void mesh_domain<Real>(const FieldMesh&, const geomipmap::Mesh&, const glm::dvec3&,    \
                                  IndexRange, DomainSpans<Real>);                                 \
  template void mesh_heights<Real>(const FieldMesh&, const geomipmap::Mesh&, double, IndexRange,  \
                                   std::span<Real>);                                              \
  template void mesh_surface<Real>(const FieldMesh&, const HeightSketch&, const geomipmap::Mesh&, \
                                   Real, bool, IndexRange, std::span<const Real>,                 \
                                   SurfaceSpans<Real>);
RELIEF_FIELD_MESH_STAGES(float)
RELIEF_FIELD_MESH_STAGES(double)

}  // namespace relief
