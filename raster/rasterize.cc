#include "raster/rasterize.h"

#include "raster/bins.h"

#include <algorithm>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace relief::raster {

namespace {

// The whole-frame rasteriser, from the pieces of bins.h: set-up in fixed chunks, the bins'
// memory checked before they are allocated, binning, then every tile into `out`.
template <class SetupOne>
RasterStats rasterize_with(const RasterState& state, std::uint32_t triangle_count,
                           SetupOne setup_one, const RasterLimits& limits,
                           TileRasterizer tile_rasterizer, VisibilityBuffer& out) {
  out = make_visibility_buffer(state);
  const TriangleSetup setup(state);
  const TileGrid tiles = make_tile_grid(state);
  const std::size_t chunk_count = setup_chunk_count(triangle_count);
  std::vector<SetupChunk> chunks(chunk_count);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunk_count, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          setup_one(setup, c, chunks[c]);
        }
      },
      tbb::simple_partitioner());
  RasterStats stats;
  stats.triangles = triangle_count;
  for (const SetupChunk& chunk : chunks) {
    stats.setup += chunk.triangles.size();
  }
  const BinSize bins = bin_size(chunks, tiles);
  stats.bin_entries = bins.entries;
  stats.bin_bytes = bins.bytes;
  if (stats.bin_bytes > limits.max_bin_bytes) {
    stats.bins_refused = true;
    return stats;
  }
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunk_count, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          bin_chunk(chunks[c], tiles);
        }
      },
      tbb::simple_partitioner());
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles.count(), 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int tile = r.begin(); tile != r.end(); ++tile) {
          if (tile_rasterizer == nullptr) {
            draw_tile(std::span<const SetupChunk>(chunks), tiles, tile, state.depth_test, out);
            continue;
          }
          const auto buffer = std::make_unique<TileVisibility>();
          tile_rasterizer(std::span<const SetupChunk>(chunks), tiles, tile, state, *buffer);
          for (int py = buffer->y0; py < buffer->y0 + buffer->height; ++py) {
            const std::size_t from = buffer->index(buffer->x0, py);
            const std::size_t to = static_cast<std::size_t>(py) * state.width + buffer->x0;
            std::copy_n(buffer->primitive + from, buffer->width, out.primitive.begin() + to);
            std::copy_n(buffer->depth + from, buffer->width, out.depth.begin() + to);
          }
        }
      },
      tbb::simple_partitioner());
  return stats;
}

}  // namespace

VisibilityBuffer make_visibility_buffer(const RasterState& state) {
  VisibilityBuffer buffer;
  buffer.width = state.width;
  buffer.height = state.height;
  const std::size_t size = static_cast<std::size_t>(state.width) * state.height;
  buffer.primitive.assign(size, kNoPrimitive);
  buffer.depth.assign(size, state.depth_clear);
  return buffer;
}

template <class Source>
RasterStats rasterize(const RasterState& state, ClipVertices vertices, const Source& source,
                      VisibilityBuffer& out, const RasterLimits& limits,
                      TileRasterizer tile_rasterizer) {
  return rasterize_with(
      state, source.count(),
      [&](const TriangleSetup& setup, std::size_t chunk, SetupChunk& into) {
        setup_chunk(setup, vertices, source, chunk, into);
      },
      limits, tile_rasterizer, out);
}

template <class Source>
RasterStats rasterize(const RasterState& state, WindowVertices vertices, const Source& source,
                      VisibilityBuffer& out, const RasterLimits& limits,
                      TileRasterizer tile_rasterizer) {
  return rasterize_with(
      state, source.count(),
      [&](const TriangleSetup& setup, std::size_t chunk, SetupChunk& into) {
        setup_window_chunk(setup, vertices, source, chunk, into);
      },
      limits, tile_rasterizer, out);
}

template RasterStats rasterize<IndexedTriangles>(const RasterState&, ClipVertices,
                                                 const IndexedTriangles&, VisibilityBuffer&,
                                                 const RasterLimits&, TileRasterizer);
template RasterStats rasterize<GridTriangles>(const RasterState&, ClipVertices,
                                              const GridTriangles&, VisibilityBuffer&,
                                              const RasterLimits&, TileRasterizer);
template RasterStats rasterize<IndexedTriangles>(const RasterState&, WindowVertices,
                                                 const IndexedTriangles&, VisibilityBuffer&,
                                                 const RasterLimits&, TileRasterizer);

}  // namespace relief::raster
