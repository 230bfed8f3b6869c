// The rasteriser's inner loop (stage 6: edge functions, depth plane, depth test) as a Highway
// kernel: raster::draw_in_tile (raster/bins.cc) for one set-up triangle in one 64 x 64 tile,
// small triangles a 4 x 4 (AVX3) or 4 x 2 (AVX2) block of pixels per step in 32-bit edge
// values, larger ones many pixels of a row per step (64-bit edge values), depth in double,
// bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace relief::simd {

// One set-up triangle (raster::RasterTriangle's fields) and its part of a tile.
struct EdgeTriangle {
  const std::int64_t* c;  // 3 edge constants
  const std::int32_t* a;  // 3 edge coefficients in x
  const std::int32_t* b;  // and in y
  int x0, x1, y0, y1;     // pixels to test, already within the tile, inclusive
  double z0, dzdx, dzdy;
  std::uint32_t primitive;
};

// raster::DepthTest's values, in its order.
enum class DepthCompare : int {
  kGreater,
  kGreaterEqual,
  kLess,
  kLessEqual,
  kEqual,
  kAlways,
  kNever
};

// The tile's buffers: 64 x 64 pixels from (x0, y0), row-major, 64 a row.
struct TileBuffers {
  int x0, y0;
  float* depth;
  std::uint32_t* primitive;
};

// Draws `count` triangles into the tile, in order (depth ties go to the first, as in GL).
void draw_triangles(const EdgeTriangle* triangles, std::size_t count, DepthCompare test,
                    const TileBuffers& tile);

}  // namespace relief::simd
