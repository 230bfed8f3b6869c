// GeoMipMapping of a finite height field (Scape's tile-based levels of detail, after de Boer
// 2000, "Fast Terrain Rendering Using Geometrical MipMapping"), with castledragmire's quadtree of
// axis-aligned bounding boxes for frustum culling. In double, once per scene (the tiles' bounds
// and errors) and once per frame (culling, levels, the stitched triangle list).
//
// The field is a lattice of vertices, (tiles_x T + 1) x (tiles_z T + 1), T = tile_cells a power
// of two: row 0 at z0, heights in world units. Tile (tx, tz) covers the cells
// [tx T, (tx + 1) T) x [tz T, (tz + 1) T). At level L a tile keeps every 2^L-th vertex of its
// lattice (L = 0 every vertex, L = log2 T its four corners).
//
// Crack-free by stitching (Scape): each tile edge is drawn at the coarser spacing of the two
// tiles that share it, the finer tile's border ring skipping the edge vertices its neighbour
// lacks (no skirts, no T-junctions). A vertex is one lattice point whichever tiles use it, so
// the mesh is watertight by construction (tests/core/geomipmap_test.cc checks every edge).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/parallel_rows.h"

namespace relief::geomipmap {

// The field's vertices: columns x rows heights, row-major, row 0 at z0; the world rectangle
// [x0, z0, x1, z1] they span (vertex (0, 0) at (x0, z0), the last at (x1, z1)).
struct FieldLattice {
  int columns = 0, rows = 0;
  std::array<double, 4> extent{};
  std::span<const float> heights;

  glm::dvec2 position(int column, int row) const;  // world (x, z)
};

// Lattices of at most this many vertices a side: vertex ids and triangle counts fit 32 bits.
inline constexpr int kMaxLatticeSide = 32769;

// What one scene's tiles keep: each tile's height range (its AABB) and, per level, its
// geometric error (de Boer's delta: the largest vertical distance between a vertex of the full
// lattice and the level's triangles over it, made non-decreasing with the level). Measured on
// every triangle the tile can draw at that level (geomipmap_triangles.h), its border's with a
// neighbour at the same level or one coarser, so it bounds the drawn mesh of any selection whose
// neighbours differ by at most one level, as select_levels' do.
struct TileBounds {
  float low = 0, high = 0;
  std::vector<double> error;  // levels entries (error[0] > 0 only from stitching)
};

struct GeoMipMap {
  int tile_cells = 0;  // T
  int levels = 0;      // log2 T + 1
  int tiles_x = 0, tiles_z = 0;
  std::array<double, 4> extent{};
  std::vector<TileBounds> tiles;  // tiles_x x tiles_z, row-major
  // The quadtree: level k (0 = the tiles) holds the height range of 2^k x 2^k tiles, the
  // last level one node for the whole field (ceil'd at odd sizes).
  struct Node {
    float low, high;
  };
  std::vector<std::vector<Node>> quadtree;
  std::vector<std::array<int, 2>> quadtree_size;  // nodes (x, z) per quadtree level
};

// Valid T: a power of two in [2, 256]; the lattice's columns - 1 and rows - 1 multiples of T.
bool valid_tile_cells(int tile_cells);
// Throws std::invalid_argument naming the size that does not fit, or the first non-finite
// height in row-major order. The rows of tiles run through `parallel` (each tile's bounds and
// errors are its own), so the map is the same bits however they ran.
GeoMipMap build_geomipmap(const FieldLattice& lattice, int tile_cells,
                          const ParallelRows& parallel = {});

// The frame's view: the camera (core/camera.h: world position in double, its axes and field
// of view, near and far), the viewport in pixels, tau, and whether to cull by occlusion.
struct View {
  CameraFrame camera;
  int width = 0, height = 0;
  double pixel_error = 1;  // tau: the largest screen-space error a level may make, pixels
  bool occlusion = true;
  int occlusion_cell = 8;  // pixels a side of the occlusion buffer's cells
};

struct SelectionCounts {
  std::uint64_t nodes_visited = 0;   // quadtree nodes tested against the frustum
  std::uint64_t nodes_culled = 0;    // of them, outside it (with every tile below)
  std::uint64_t tiles_culled = 0;    // tiles outside the frustum
  std::uint64_t tiles_occluded = 0;  // tiles in it, hidden behind nearer ground
  std::uint64_t tiles_drawn = 0;
  std::uint64_t tiles_per_level[9] = {};  // drawn tiles by level (T <= 256: 9 levels)
  std::uint64_t occlusion_cells = 0;      // occlusion buffer cells an occluder covered
};

struct Selection {
  std::vector<int> level;           // per tile, every tile (a culled one's too: its
                                    // neighbours stitch to it, so culling removes
                                    // triangles and changes none)
  std::vector<std::uint8_t> drawn;  // per tile: 1 drawn, 0 culled or occluded
  // Per tile: 1 where occlusion culling removed it (drawn 0); empty where it did not run.
  std::vector<std::uint8_t> occluded;
  SelectionCounts counts;
};

// Quadtree frustum culling, each tile's level (the coarsest L whose error, seen from the
// nearest point of the tile's AABB, is at most tau pixels: error[L] ppt / distance <= tau, ppt
// = height / (2 tan(fov_y / 2)); level 0 where the camera is inside the box or none fits), then
// levels lowered until neighbours differ by at most one (a finer level only lowers the error,
// so every tile still meets tau), then occlusion culling
// (core/heightfield/geomipmap_select.cc says when it is sound and why).
Selection select_levels(const GeoMipMap& map, const View& view);

// The stitched triangle list of the drawn tiles (each side at the coarser spacing of its two
// tiles' levels, whether the neighbour is drawn or not; watertight for any levels, within
// each tile's error where neighbours differ by at most one): vertex i is the lattice point
// (vertex_column[i], vertex_row[i]), each point once; indices 3 per triangle, counter-clockwise
// seen from above (+y). Tiles in row-major order, each tile's triangles in a fixed order.
struct Mesh {
  std::vector<std::int32_t> vertex_column, vertex_row;
  std::vector<std::uint32_t> indices;
  // The drawn tiles in order, and where each one's triangles begin (one more entry: the end).
  std::vector<std::uint32_t> tiles, tile_first_triangle;
  // Per drawn tile (one more entry: the end), the stable number of its first triangle: its
  // place in the list the selection would give without occlusion culling (an occluded tile's
  // triangles counted as if drawn), so that the frame's primitive output is the same with the
  // skip on or off (stable_primitive_ids).
  std::vector<std::uint32_t> tile_first_id;
};
Mesh stitched_mesh(const GeoMipMap& map, const Selection& selection);

// Triangle numbers of `mesh`'s list turned into its stable ones (Mesh::tile_first_id), in
// place; raster::kNoPrimitive (0xffffffff) and numbers past the list stay as they are.
void stable_primitive_ids(const Mesh& mesh, std::span<std::uint32_t> primitive);

}  // namespace relief::geomipmap
