#include "raster/rasterize.h"

#include <algorithm>
#include <atomic>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace relief::raster {

namespace {

// The set-up triangles of one chunk and its bins: the entries of tile k are
// entries[tile_start[k] .. tile_start[k + 1]), indices into triangles, in submission order.
struct SetupChunk {
  std::vector<RasterTriangle> triangles;
  std::vector<std::uint32_t> tile_start;
  std::vector<std::uint32_t> entries;
};

struct TileGrid {
  int columns;
  int rows;
  int count() const { return columns * rows; }
};

// Tiles a triangle's bounding box touches: its bin entries.
std::uint64_t tiles_touched(const RasterTriangle& t) {
  return std::uint64_t(t.x1 / kTileSize - t.x0 / kTileSize + 1) *
         std::uint64_t(t.y1 / kTileSize - t.y0 / kTileSize + 1);
}

void bin_chunk(SetupChunk& chunk, const TileGrid& tiles) {
  chunk.tile_start.assign(static_cast<std::size_t>(tiles.count()) + 1, 0);
  for (const RasterTriangle& t : chunk.triangles) {
    for (int ty = t.y0 / kTileSize; ty <= t.y1 / kTileSize; ++ty) {
      for (int tx = t.x0 / kTileSize; tx <= t.x1 / kTileSize; ++tx) {
        ++chunk.tile_start[static_cast<std::size_t>(ty) * tiles.columns + tx + 1];
      }
    }
  }
  for (std::size_t k = 1; k < chunk.tile_start.size(); ++k) {
    chunk.tile_start[k] += chunk.tile_start[k - 1];
  }
  chunk.entries.resize(chunk.tile_start.back());
  std::vector<std::uint32_t> cursor(chunk.tile_start.begin(), chunk.tile_start.end() - 1);
  for (std::uint32_t index = 0; index < chunk.triangles.size(); ++index) {
    const RasterTriangle& t = chunk.triangles[index];
    for (int ty = t.y0 / kTileSize; ty <= t.y1 / kTileSize; ++ty) {
      for (int tx = t.x0 / kTileSize; tx <= t.x1 / kTileSize; ++tx) {
        chunk.entries[cursor[static_cast<std::size_t>(ty) * tiles.columns + tx]++] = index;
      }
    }
  }
}

bool depth_passes(DepthTest test, float incoming, float stored) {
  switch (test) {
    case DepthTest::kGreater:
      return incoming > stored;
    case DepthTest::kGreaterEqual:
      return incoming >= stored;
    case DepthTest::kLess:
      return incoming < stored;
    case DepthTest::kLessEqual:
      return incoming <= stored;
    case DepthTest::kEqual:
      return incoming == stored;
    case DepthTest::kAlways:
      return true;
    case DepthTest::kNever:
      return false;
  }
  return false;
}

// Draws one triangle into the part of the buffer inside tile (tx, ty). Edge functions are
// stepped exactly: +a_i * 256 per pixel to the right.
void rasterize_in_tile(const RasterTriangle& t, int tx, int ty, DepthTest test,
                       VisibilityBuffer& out) {
  const int x0 = std::max(t.x0, tx * kTileSize);
  const int x1 = std::min(t.x1, tx * kTileSize + kTileSize - 1);
  const int y0 = std::max(t.y0, ty * kTileSize);
  const int y1 = std::min(t.y1, ty * kTileSize + kTileSize - 1);
  const std::int64_t step[3] = {std::int64_t{t.a[0]} * kSubpixelScale,
                                std::int64_t{t.a[1]} * kSubpixelScale,
                                std::int64_t{t.a[2]} * kSubpixelScale};
  for (int py = y0; py <= y1; ++py) {
    const std::int64_t fx = std::int64_t{x0} * kSubpixelScale;
    const std::int64_t fy = std::int64_t{py} * kSubpixelScale;
    std::int64_t e0 = t.a[0] * fx + t.b[0] * fy + t.c[0];
    std::int64_t e1 = t.a[1] * fx + t.b[1] * fy + t.c[1];
    std::int64_t e2 = t.a[2] * fx + t.b[2] * fy + t.c[2];
    for (int px = x0; px <= x1; ++px) {
      if ((e0 > 0) & (e1 > 0) & (e2 > 0)) {
        const float depth = t.depth(px, py);
        const std::size_t k = out.index(px, py);
        if (depth_passes(test, depth, out.depth[k])) {
          out.depth[k] = depth;
          out.primitive[k] = t.primitive;
        }
      }
      e0 += step[0];
      e1 += step[1];
      e2 += step[2];
    }
  }
}

template <class SetupOne>
RasterStats rasterize_with(const RasterState& state, std::uint32_t triangle_count,
                           SetupOne setup_one, const RasterLimits& limits, VisibilityBuffer& out) {
  out = make_visibility_buffer(state);
  const TriangleSetup setup(state);
  const TileGrid tiles{(state.width + kTileSize - 1) / kTileSize,
                       (state.height + kTileSize - 1) / kTileSize};
  const std::size_t chunk_count = (triangle_count + kSetupChunk - 1) / kSetupChunk;
  std::vector<SetupChunk> chunks(chunk_count);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunk_count, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          const std::uint32_t begin = static_cast<std::uint32_t>(c * kSetupChunk);
          const std::uint32_t end = std::min(triangle_count, begin + kSetupChunk);
          for (std::uint32_t t = begin; t < end; ++t) {
            setup_one(setup, t, chunks[c].triangles);
          }
        }
      },
      tbb::simple_partitioner());
  RasterStats stats;
  stats.triangles = triangle_count;
  // Per chunk: the tile offsets and the fill cursors, (tiles + 1) + tiles entries.
  stats.bin_bytes = chunk_count * (2 * std::uint64_t(tiles.count()) + 1) * sizeof(std::uint32_t);
  for (const SetupChunk& chunk : chunks) {
    stats.setup += chunk.triangles.size();
    for (const RasterTriangle& t : chunk.triangles) {
      stats.bin_entries += tiles_touched(t);
    }
  }
  stats.bin_bytes += stats.bin_entries * sizeof(std::uint32_t);
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
          const int tx = tile % tiles.columns;
          const int ty = tile / tiles.columns;
          for (const SetupChunk& chunk : chunks) {
            for (std::uint32_t e = chunk.tile_start[tile]; e < chunk.tile_start[tile + 1]; ++e) {
              rasterize_in_tile(chunk.triangles[chunk.entries[e]], tx, ty, state.depth_test, out);
            }
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
                      VisibilityBuffer& out, const RasterLimits& limits) {
  return rasterize_with(
      state, source.count(),
      [&](const TriangleSetup& setup, std::uint32_t t, std::vector<RasterTriangle>& triangles) {
        std::uint32_t v[3];
        if (!source.vertices(t, v)) {
          return;
        }
        const ClipVertex clip[3] = {
            {vertices.x[v[0]], vertices.y[v[0]], vertices.z[v[0]], vertices.w[v[0]]},
            {vertices.x[v[1]], vertices.y[v[1]], vertices.z[v[1]], vertices.w[v[1]]},
            {vertices.x[v[2]], vertices.y[v[2]], vertices.z[v[2]], vertices.w[v[2]]}};
        setup.setup_clip(t, clip, triangles);
      },
      limits, out);
}

template <class Source>
RasterStats rasterize(const RasterState& state, WindowVertices vertices, const Source& source,
                      VisibilityBuffer& out, const RasterLimits& limits) {
  return rasterize_with(
      state, source.count(),
      [&](const TriangleSetup& setup, std::uint32_t t, std::vector<RasterTriangle>& triangles) {
        std::uint32_t v[3];
        if (!source.vertices(t, v)) {
          return;
        }
        const float x[3] = {vertices.x[v[0]], vertices.x[v[1]], vertices.x[v[2]]};
        const float y[3] = {vertices.y[v[0]], vertices.y[v[1]], vertices.y[v[2]]};
        const float z[3] = {vertices.z[v[0]], vertices.z[v[1]], vertices.z[v[2]]};
        setup.setup_window(t, x, y, z, triangles);
      },
      limits, out);
}

template RasterStats rasterize<IndexedTriangles>(const RasterState&, ClipVertices,
                                                 const IndexedTriangles&, VisibilityBuffer&,
                                                 const RasterLimits&);
template RasterStats rasterize<GridTriangles>(const RasterState&, ClipVertices,
                                              const GridTriangles&, VisibilityBuffer&,
                                              const RasterLimits&);
template RasterStats rasterize<IndexedTriangles>(const RasterState&, WindowVertices,
                                                 const IndexedTriangles&, VisibilityBuffer&,
                                                 const RasterLimits&);

}  // namespace relief::raster
