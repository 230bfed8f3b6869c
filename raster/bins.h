// Stage 6 in the pieces a frame schedules one by one (the frame's stage table runs each over
// its own units of work): triangle set-up in fixed chunks, binning of each chunk's triangles
// into 64 x 64 screen tiles, and rasterisation of one tile into a tile-local visibility buffer.
//
// Each chunk's triangles keep submission order, and a tile visits the chunks in order, so the
// depth test sees triangles in submission order (on equal depth the first submitted wins, as in
// GL) and a tile's result never depends on which thread set up which chunk.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/raster_types.h"
#include "raster/topology.h"
#include "raster/triangle_setup.h"

namespace relief::raster {

// The set-up triangles of one chunk and its bins: the entries of tile k are
// entries[tile_start[k] .. tile_start[k + 1]), indices into triangles, in submission order.
struct SetupChunk {
  std::uint32_t submitted = 0;  // triangles of the chunk its source draws (before culling)
  RasterTriangles triangles;
  std::uint64_t bin_entries = 0;  // tiles the triangles' bounding boxes touch, summed
  std::vector<std::uint32_t> tile_start;
  std::vector<std::uint32_t> entries;
};

struct TileGrid {
  int columns = 0;
  int rows = 0;
  int count() const { return columns * rows; }
};

TileGrid make_tile_grid(const RasterState& state);

// Chunks of kSetupChunk triangles for `triangle_count` triangles.
inline std::size_t setup_chunk_count(std::uint32_t triangle_count) {
  return (std::size_t(triangle_count) + kSetupChunk - 1) / kSetupChunk;
}

// Sets up the triangles of chunk `chunk` (triangles chunk * kSetupChunk onwards) of `source`,
// whose vertex positions are `vertices`, into out.triangles (cleared first); sets
// out.submitted and out.bin_entries.
template <class Source>
void setup_chunk(const TriangleSetup& setup, ClipVertices vertices, const Source& source,
                 std::size_t chunk, SetupChunk& out);

// The same for an index list whose vertices are prepared in blocks (setup_indexed): the same
// triangles, counts and entries as setup_chunk<IndexedTriangles> gives.
void setup_indexed_chunk(const TriangleSetup& setup, ClipVertices vertices,
                         const IndexedTriangles& source, std::span<const PreparedVertices> blocks,
                         std::size_t block_vertices, std::size_t chunk, SetupChunk& out);

// The same for window-coordinate triangles (relief raster's soups).
void setup_window_chunk(const TriangleSetup& setup, WindowVertices vertices,
                        const IndexedTriangles& source, std::size_t chunk, SetupChunk& out);

// Memory the bins of `chunks` will take once binned (entries counted from the triangles'
// bounding boxes, as setup_chunk and setup_window_chunk left them in bin_entries, plus each
// chunk's tile offsets and fill cursors), and the entries alone.
struct BinSize {
  std::uint64_t entries = 0;
  std::uint64_t bytes = 0;
};
BinSize bin_size(std::span<const SetupChunk> chunks, const TileGrid& tiles);

// Fills chunk.tile_start and chunk.entries.
void bin_chunk(SetupChunk& chunk, const TileGrid& tiles);

// The (triangle, tile) entries binned to tile `tile` over all chunks: 0 for a tile no
// triangle's bounding box touches.
std::uint64_t tile_entry_count(std::span<const SetupChunk> chunks, int tile);

// The visibility of one tile: pixels [x0, x0 + width) x [y0, y0 + height) of the framebuffer,
// row-major from the tile's bottom row, kTileSize pixels a row.
struct TileVisibility {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::uint32_t primitive[kTileSize * kTileSize];
  float depth[kTileSize * kTileSize];

  std::size_t index(int px, int py) const {
    return static_cast<std::size_t>(py - y0) * kTileSize + static_cast<std::size_t>(px - x0);
  }
};

// Clears `out` to (kNoPrimitive, depth_clear) and draws every triangle binned to tile `tile`,
// chunk by chunk in order, with the state's depth test.
void rasterize_tile(std::span<const SetupChunk> chunks, const TileGrid& tiles, int tile,
                    const RasterState& state, TileVisibility& out);

// Only the clear of rasterize_tile: for a tile no triangle is binned to.
void clear_tile(const TileGrid& tiles, int tile, const RasterState& state, TileVisibility& out);

// The same, drawing into the tile's pixels of a whole visibility buffer (already cleared).
template <class Target>
void draw_tile(std::span<const SetupChunk> chunks, const TileGrid& tiles, int tile, DepthTest test,
               Target& out);

}  // namespace relief::raster
