#include "raster/bins.h"

#include <algorithm>
#include <type_traits>

#include "raster/topology.h"

namespace relief::raster {

namespace {

// Tiles a triangle's bounding box touches: its bin entries.
std::uint64_t tiles_touched(const RasterTriangle& t) {
  return std::uint64_t(t.x1 / kTileSize - t.x0 / kTileSize + 1) *
         std::uint64_t(t.y1 / kTileSize - t.y0 / kTileSize + 1);
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

template <class Source>
std::uint32_t chunk_end(const Source& source, std::size_t chunk) {
  return static_cast<std::uint32_t>(
      std::min<std::size_t>(source.count(), (chunk + 1) * std::size_t(kSetupChunk)));
}

}  // namespace

TileGrid make_tile_grid(const RasterState& state) {
  return {(state.width + kTileSize - 1) / kTileSize, (state.height + kTileSize - 1) / kTileSize};
}

namespace {

// Calls set_up_one(t, v) for each drawn triangle t of chunk `chunk`, v its vertex indices.
template <class Source, class SetUpOne>
void for_each_triangle_of_chunk(const Source& source, std::size_t chunk, SetUpOne set_up_one) {
  const auto begin = static_cast<std::uint32_t>(chunk * kSetupChunk);
  for (std::uint32_t t = begin; t < chunk_end(source, chunk); ++t) {
    std::uint32_t v[3];
    if (source.vertices(t, v)) {
      set_up_one(t, v);
    }
  }
}

// A thread's buffer for one chunk's triangles, reused chunk after chunk (cleared here), so
// that the chunk's own storage is allocated once, at its size.
std::vector<RasterTriangle>& chunk_scratch() {
  thread_local std::vector<RasterTriangle> pieces;
  pieces.clear();
  return pieces;
}

// The bin entries of a chunk's triangles, counted while they are in cache (bin_size).
std::uint64_t count_bin_entries(const RasterTriangles& triangles) {
  std::uint64_t entries = 0;
  for (const RasterTriangle& t : triangles) {
    entries += tiles_touched(t);
  }
  return entries;
}

}  // namespace

template <class Source>
void setup_chunk(const TriangleSetup& setup, ClipVertices vertices, const Source& source,
                 std::size_t chunk, SetupChunk& out) {
  out.triangles.clear();
  out.submitted = 0;
  if constexpr (std::is_same_v<Source, GridTriangles>) {
    // Each vertex of the chunk's triangles prepared once, then the triangles from those values.
    const auto begin = static_cast<std::uint32_t>(chunk * kSetupChunk);
    const std::uint32_t end = chunk_end(source, chunk);
    if (begin < end) {
      thread_local PreparedVertices prepared;  // scratch, filled before every use
      const GridTriangles::VertexSpan span = source.vertex_span(begin, end);
      setup.prepare_vertices(vertices, span.first, span.last, source.valid, source.need, prepared);
      setup.setup_grid(vertices, source, begin, end, prepared, out.submitted, out.triangles);
    }
  } else {
    std::vector<RasterTriangle>& pieces = chunk_scratch();
    for_each_triangle_of_chunk(source, chunk, [&](std::uint32_t t, const std::uint32_t v[3]) {
      ++out.submitted;
      const ClipVertex clip[3] = {
          {vertices.x[v[0]], vertices.y[v[0]], vertices.z[v[0]], vertices.w[v[0]]},
          {vertices.x[v[1]], vertices.y[v[1]], vertices.z[v[1]], vertices.w[v[1]]},
          {vertices.x[v[2]], vertices.y[v[2]], vertices.z[v[2]], vertices.w[v[2]]}};
      setup.setup_clip(t, clip, pieces);
    });
    out.triangles.assign(pieces.begin(), pieces.end());
  }
  out.bin_entries = count_bin_entries(out.triangles);
}

void setup_indexed_chunk(const TriangleSetup& setup, ClipVertices vertices,
                         const IndexedTriangles& source, std::span<const PreparedVertices> blocks,
                         std::size_t block_vertices, std::size_t chunk, SetupChunk& out) {
  out.triangles.clear();
  out.submitted = 0;
  const auto begin = static_cast<std::uint32_t>(chunk * kSetupChunk);
  setup.setup_indexed(vertices, source, begin, chunk_end(source, chunk), blocks, block_vertices,
                      out.submitted, out.triangles);
  out.bin_entries = count_bin_entries(out.triangles);
}

void setup_window_chunk(const TriangleSetup& setup, WindowVertices vertices,
                        const IndexedTriangles& source, std::size_t chunk, SetupChunk& out) {
  out.triangles.clear();
  out.submitted = 0;
  std::vector<RasterTriangle>& pieces = chunk_scratch();
  for_each_triangle_of_chunk(source, chunk, [&](std::uint32_t t, const std::uint32_t v[3]) {
    ++out.submitted;
    const float x[3] = {vertices.x[v[0]], vertices.x[v[1]], vertices.x[v[2]]};
    const float y[3] = {vertices.y[v[0]], vertices.y[v[1]], vertices.y[v[2]]};
    const float z[3] = {vertices.z[v[0]], vertices.z[v[1]], vertices.z[v[2]]};
    setup.setup_window(t, x, y, z, pieces);
  });
  out.triangles.assign(pieces.begin(), pieces.end());
  out.bin_entries = count_bin_entries(out.triangles);
}

BinSize bin_size(std::span<const SetupChunk> chunks, const TileGrid& tiles) {
  BinSize size;
  for (const SetupChunk& chunk : chunks) {
    size.entries += chunk.bin_entries;
  }
  // Per chunk: the tile offsets and the fill cursors, (tiles + 1) + tiles entries.
  size.bytes = (chunks.size() * (2 * std::uint64_t(tiles.count()) + 1) + size.entries) *
               sizeof(std::uint32_t);
  return size;
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

// Draws one triangle into the pixels of `target` inside tile (tx, ty). Edge functions are
// stepped exactly: +a_i * 256 per pixel to the right. `target` is a TileVisibility or a whole
// VisibilityBuffer (index(px, py), depth[], primitive[]).
template <class Target>
void draw_in_tile(const RasterTriangle& t, int tx, int ty, DepthTest test, Target& out) {
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

template <class Target>
void draw_tile(std::span<const SetupChunk> chunks, const TileGrid& tiles, int tile, DepthTest test,
               Target& out) {
  const int tx = tile % tiles.columns;
  const int ty = tile / tiles.columns;
  for (const SetupChunk& chunk : chunks) {
    for (std::uint32_t e = chunk.tile_start[tile]; e < chunk.tile_start[tile + 1]; ++e) {
      draw_in_tile(chunk.triangles[chunk.entries[e]], tx, ty, test, out);
    }
  }
}

std::uint64_t tile_entry_count(std::span<const SetupChunk> chunks, int tile) {
  std::uint64_t entries = 0;
  for (const SetupChunk& chunk : chunks) {
    entries += chunk.tile_start[tile + 1] - chunk.tile_start[tile];
  }
  return entries;
}

void clear_tile(const TileGrid& tiles, int tile, const RasterState& state, TileVisibility& out) {
  out.x0 = tile % tiles.columns * kTileSize;
  out.y0 = tile / tiles.columns * kTileSize;
  out.width = std::min(kTileSize, state.width - out.x0);
  out.height = std::min(kTileSize, state.height - out.y0);
  std::fill(std::begin(out.primitive), std::end(out.primitive), kNoPrimitive);
  std::fill(std::begin(out.depth), std::end(out.depth), state.depth_clear);
}

void rasterize_tile(std::span<const SetupChunk> chunks, const TileGrid& tiles, int tile,
                    const RasterState& state, TileVisibility& out) {
  clear_tile(tiles, tile, state, out);
  draw_tile(chunks, tiles, tile, state.depth_test, out);
}

template void setup_chunk<IndexedTriangles>(const TriangleSetup&, ClipVertices,
                                            const IndexedTriangles&, std::size_t, SetupChunk&);
template void setup_chunk<GridTriangles>(const TriangleSetup&, ClipVertices, const GridTriangles&,
                                         std::size_t, SetupChunk&);
template void draw_tile<VisibilityBuffer>(std::span<const SetupChunk>, const TileGrid&, int,
                                          DepthTest, VisibilityBuffer&);

}  // namespace relief::raster
