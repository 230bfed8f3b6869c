// Stage 6: rasterisation into the visibility buffer (docs/architecture.md), the way GL hardware
// does it.
//
// 1. Setup, in parallel over fixed chunks of kSetupChunk triangles (triangle_setup.h), and
//    binning of each chunk's triangles into 64 x 64 screen tiles, in submission order.
// 2. Each tile is rasterised independently (its own task; no two tasks write the same pixel),
//    visiting the chunks in order and each chunk's triangles in order: the depth test sees
//    triangles in submission order, so on equal depth the first submitted wins under GREATER
//    and LESS, as in GL. The buffer is therefore identical for every thread count.
#pragma once

#include <cstdint>
#include <span>

#include "raster/bins.h"
#include "raster/raster_types.h"
#include "raster/topology.h"
#include "raster/triangle_setup.h"

namespace relief::raster {

// The bins are the one allocation whose size the caller cannot know in advance: a triangle
// enters every tile its bounding box touches, so 100,000 full-screen triangles at 16384^2 need
// 26 GB of bin entries. They are counted (from the bounding boxes, in O(triangles)) before
// they are allocated, and a frame whose bins exceed the limit is not drawn.
struct RasterLimits {
  std::uint64_t max_bin_bytes = UINT64_MAX;
};

// Draws the triangles binned to one tile into a tile-sized buffer, as rasterize_tile does
// (bins.h); another implementation (the SIMD kernels of pipeline/tile_pass.h) may stand in
// for it, with the same bytes.
using TileRasterizer = void (*)(std::span<const SetupChunk> chunks, const TileGrid& tiles, int tile,
                                const RasterState& state, TileVisibility& out);

struct RasterStats {
  std::uint64_t triangles = 0;    // triangles submitted
  std::uint64_t setup = 0;        // rasterisable pieces after culling and clipping
  std::uint64_t bin_entries = 0;  // (triangle, tile) pairs
  std::uint64_t bin_bytes = 0;    // memory of the bins (entries and per-chunk tile offsets)
  std::uint64_t setup_bytes = 0;  // memory of the set-up triangles (the chunks' storage)
  bool bins_refused = false;      // bin_bytes > max_bin_bytes: nothing was drawn
};

// Clears `out` to (kNoPrimitive, depth_clear) at the state's size and draws every triangle of
// `source`. Vertex positions are indexed by the source's vertex indices.
// `tile_rasterizer` null: the tiles are drawn straight into `out`.
template <class Source>
RasterStats rasterize(const RasterState& state, ClipVertices vertices, const Source& source,
                      VisibilityBuffer& out, const RasterLimits& limits = {},
                      TileRasterizer tile_rasterizer = nullptr);
template <class Source>
RasterStats rasterize(const RasterState& state, WindowVertices vertices, const Source& source,
                      VisibilityBuffer& out, const RasterLimits& limits = {},
                      TileRasterizer tile_rasterizer = nullptr);

// Calls f(px, py) for every pixel the triangle covers, row by row from the bottom.
template <class F>
void for_each_covered_pixel(const RasterTriangle& t, F&& f) {
  for (int py = t.y0; py <= t.y1; ++py) {
    for (int px = t.x0; px <= t.x1; ++px) {
      if (t.covers(px, py)) {
        f(px, py);
      }
    }
  }
}

}  // namespace relief::raster
