// A finite height field drawn by GeoMipMapping (geomipmap.h) instead of the projected grid:
// once per scene the lattice of the field's surface at its sample positions and its tiles;
// once per frame the stitched mesh of the tiles the view selects, and the stages 2-4 of its
// vertices (camera-relative positions, heights, normals), written into the grid buffers of
// core/grid_buffers.h laid out as rows of kMeshRowVertices vertices, so that stage 5 onwards
// runs on them unchanged and the rasteriser draws the mesh's index list.
//
// The surface is the field's own (core/height_sketch.h): the uniform cubic B-spline of its
// texels (or, `interpolating`, of the coefficients that pass through the samples). Lattice
// vertex (c, r) sits at texel (c, r)'s centre, x0 + (c + 1/2) (x1 - x0) / W, and its height is
// the B-spline there: the taps (1, 4, 1) / 6 along each axis, the edge texels extended
// (GL_CLAMP_TO_EDGE, as the projected grid reads them). The lattice has whole tiles:
// ceil((W - 1) / T) T + 1 vertices along x (likewise z), up to T - 1 of them beyond the last
// texel centre on the extended edge (a field smaller than a tile grows with T). Its normals are the
// B-spline's own gradient at the vertex, at the field's full resolution whatever the tile's level
// (a normal does not pop with the level).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/grid_buffers.h"
#include "core/height_sketch.h"
#include "core/heightfield/geomipmap.h"
#include "core/parallel_rows.h"

namespace relief {

// The mesh's vertices fill rows of this many (a multiple of every vector width): the grid
// stages' rows are their unit of parallel work.
inline constexpr int kMeshRowVertices = 4096;
// The rasteriser prepares (snaps) the mesh's vertices once per frame, in blocks of this many.
inline constexpr std::size_t kMeshPreparedBlock = 16384;

struct FieldMesh {
  int columns = 0, rows = 0;       // lattice vertices along x and z
  std::array<double, 4> extent{};  // world (x, z) of vertex (0, 0) and of the last one
  double cell_x = 0, cell_z = 0;   // world units between neighbouring vertices (> 0)
  // The field's heights above terrain.base_height, row-major: the world height is base_height
  // plus this, added in double per frame (with the camera's, stage 3), so a large base height
  // costs no precision; the tiles' bounds are the same relative heights, and the frame selects
  // tiles with the camera's height above the base.
  std::vector<float> heights;
  geomipmap::GeoMipMap map;

  geomipmap::FieldLattice lattice() const { return {columns, rows, extent, heights}; }
  // Bytes held per lattice vertex and per tile (the job's memory estimate).
  static constexpr std::uintmax_t kBytesPerVertex = sizeof(float);
};

// The lattice of `field` (level 0 of its texels) over `extent`, and its GeoMipMap with tiles of
// `tile_cells` (a power of two, 2..256). Throws std::invalid_argument as build_geomipmap does.
// The lattice's rows and the tiles' rows run through `parallel` (core/parallel_rows.h).
FieldMesh build_field_mesh(const HeightSketch& field, const std::array<double, 4>& extent,
                           int tile_cells, const ParallelRows& parallel = {});

// Lattice vertices of a field of `width` x `height` texels in tiles of `tile_cells`.
std::uintmax_t field_mesh_vertices(int width, int height, int tile_cells);

// The grid layout the mesh's vertices fill: kMeshRowVertices a row, the last row padded
// (valid = 0); at least one row.
GridLayout mesh_layout(std::size_t vertices);

// Stage 2 for the mesh: vertex k's camera-relative (dx, dz), formed in double from its lattice
// position and the camera's and rounded once; sigma the lattice spacing, nu 0 (no octave),
// valid 1; padding: 0 and valid 0. Over flat indices `range` of `layout`.
template <class Real>
void mesh_domain(const FieldMesh& field, const geomipmap::Mesh& mesh, const glm::dvec3& camera,
                 IndexRange range, DomainSpans<Real> out);

// Stage 3: vertex k's camera-relative height, its lattice height minus the camera's height above
// terrain.base_height (formed in double by the caller), in double, rounded once.
template <class Real>
void mesh_heights(const FieldMesh& field, const geomipmap::Mesh& mesh, double camera_above_base,
                  IndexRange range, std::span<Real> height);

// Stage 4: the B-spline's gradient g at the vertex, in double from the texels (d/dx: the
// central difference of the texel columns on either side over 2 cell_x, weighted (1, 4, 1) / 6
// along z; d/dz likewise), the normal (-g_x, 1, -g_z) / |.|, slope |g| (at most kMaxSlope), and
// the water depth max(0, water_level - h) where water is enabled (params as stage 4's).
// `field` holds the texels (level 0 of `texels`, `width` x `height`).
template <class Real>
void mesh_surface(const FieldMesh& field, const HeightSketch& texels, const geomipmap::Mesh& mesh,
                  Real water_level, bool water, IndexRange range, std::span<const Real> height,
                  SurfaceSpans<Real> out);

}  // namespace relief
