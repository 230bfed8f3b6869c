// The rasteriser's Highway inner loop (simd/raster_tile.h) on boxes of every awkward width
// (tests/simd/kernel_ranges.h) on every target this CPU runs: the depths and primitives it
// writes are raster's draw_tile's (raster/bins.h) bit for bit, and no pixel outside the box is
// written. The boxes lie against the tile's left and bottom edges and against its right and top
// edges, at 0, 1 and 5 pixels from them, so the 4 x 4 blocks (4 x 2 on AVX2) of small triangles
// and the rows of large ones end inside a vector, and are moved inside the tile at its edges.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "raster/bins.h"
#include "raster/raster_types.h"
#include "raster/triangle_setup.h"
#include "simd/raster_tile.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

using raster::kTileSize;

// One triangle in window coordinates covering the whole 64 x 64 tile at the origin, set up by
// raster: `span` pixels along its legs. Below 256 pixels its edge coefficients fit the block
// path's limit (2^16 in 1/256-pixel units), above it they take the 64-bit rows.
raster::RasterTriangle covering_triangle(float span) {
  raster::RasterState state;
  state.width = state.height = kTileSize;
  state.viewport = {0, 0, double(kTileSize), double(kTileSize)};
  state.cull = raster::CullMode::kNone;
  const raster::TriangleSetup setup(state);
  const float x[3] = {-10.0f, span - 10.0f, -10.0f};
  const float y[3] = {-10.0f, -10.0f, span - 10.0f};
  const float z[3] = {0.25f, 0.5f, 0.75f};  // a sloping depth plane
  std::vector<raster::RasterTriangle> out;
  setup.setup_window(7, x, y, z, out);
  REQUIRE(out.size() == 1);
  return out[0];
}

// A tile whose pixels hold the sentinel, but for the box's depths where the depth test reads
// them: cleared to 0, which every depth of the triangle passes with kGreater.
struct TileContents {
  std::vector<float> depth;
  std::vector<std::uint32_t> primitive;

  TileContents(const raster::RasterTriangle& box, raster::DepthTest test)
      : depth(kTileSize * kTileSize, test::sentinel<float>()),
        primitive(kTileSize * kTileSize, test::sentinel<std::uint32_t>()) {
    for (int py = box.y0; test != raster::DepthTest::kAlways && py <= box.y1; ++py) {
      for (int px = box.x0; px <= box.x1; ++px) {
        depth[std::size_t(py) * kTileSize + std::size_t(px)] = 0.0f;
      }
    }
  }
};

// Whether the pixels outside the box still hold the sentinel, and those inside the primitive
// (the triangle covers the whole tile, and its depths pass).
bool wrote_exactly_the_box(const TileContents& tile, const raster::RasterTriangle& box) {
  for (int py = 0; py < kTileSize; ++py) {
    for (int px = 0; px < kTileSize; ++px) {
      const std::size_t k = std::size_t(py) * kTileSize + std::size_t(px);
      const bool inside = px >= box.x0 && px <= box.x1 && py >= box.y0 && py <= box.y1;
      const std::uint32_t expected = inside ? box.primitive : test::sentinel<std::uint32_t>();
      if (tile.primitive[k] != expected) {
        return false;
      }
      const float untouched = test::sentinel<float>();
      if (!inside && std::memcmp(&tile.depth[k], &untouched, sizeof(float)) != 0) {
        return false;
      }
    }
  }
  return true;
}

// raster's scalar loop over the one triangle binned to tile 0.
void draw_scalar(const raster::RasterTriangle& t, raster::DepthTest test, TileContents& out) {
  raster::SetupChunk chunk;
  chunk.triangles.push_back(t);
  chunk.tile_start = {0, 1};
  chunk.entries = {0};
  raster::TileGrid tiles;
  tiles.columns = tiles.rows = 1;
  raster::VisibilityBuffer visibility;  // a 64 x 64 framebuffer: pixel (px, py) at py * 64 + px
  visibility.width = visibility.height = kTileSize;
  visibility.depth.assign(out.depth.begin(), out.depth.end());
  visibility.primitive.assign(out.primitive.begin(), out.primitive.end());
  raster::draw_tile(std::span<const raster::SetupChunk>(&chunk, 1), tiles, 0, test, visibility);
  std::copy(visibility.depth.begin(), visibility.depth.end(), out.depth.begin());
  std::copy(visibility.primitive.begin(), visibility.primitive.end(), out.primitive.begin());
}

void draw_simd(const raster::RasterTriangle& t, std::size_t count, raster::DepthTest test,
               TileContents& out) {
  const simd::EdgeTriangle triangle{t.c,  t.a,  t.b,    t.x0,   t.x1,       t.y0,
                                    t.y1, t.z0, t.dzdx, t.dzdy, t.primitive};
  simd::draw_triangles(&triangle, count, simd::DepthCompare(int(test)),
                       {0, 0, out.depth.data(), out.primitive.data()});
}

TEST_CASE("simdRasterLoopOnAwkwardBoxesIsTheScalarLoopAndWritesOnlyItsBox", "[simd]") {
  const EachTarget targets;
  for (const float span : {200.0f, 900.0f}) {
    const raster::RasterTriangle whole = covering_triangle(span);
    for (const raster::DepthTest test : {raster::DepthTest::kAlways, raster::DepthTest::kGreater}) {
      for (const std::size_t width : test::awkward_lengths()) {
        for (const std::size_t from_edge : test::kRangeStarts) {
          for (const int rows : {1, 3, 5}) {
            for (const bool near_origin : {true, false}) {
              // The box: `width` x `rows` pixels, `from_edge` from the tile's left and bottom
              // edges or from its right and top ones.
              raster::RasterTriangle box = whole;
              const int w = int(width), gap = int(from_edge);
              box.x0 = near_origin ? gap : kTileSize - gap - w;
              box.x1 = box.x0 + w - 1;
              box.y0 = near_origin ? gap : kTileSize - gap - rows;
              box.y1 = box.y0 + rows - 1;
              TileContents expected(box, test);
              draw_scalar(box, test, expected);
              INFO("span " << span << ", depth test " << int(test) << ", box " << box.x0 << ".."
                           << box.x1 << " x " << box.y0 << ".." << box.y1);
              REQUIRE(wrote_exactly_the_box(expected, box));
              for (const std::string& target : targets.runnable()) {
                simd::force_target(target);
                TileContents got(box, test);
                draw_simd(box, 1, test, got);
                INFO(target);
                CHECK(test::same_bits(got.depth, expected.depth));
                CHECK(test::same_bits(got.primitive, expected.primitive));
              }
            }
          }
        }
      }
    }
  }
  // No triangle at all: nothing written.
  const raster::RasterTriangle whole = covering_triangle(200.0f);
  for (const std::string& target : targets.runnable()) {
    simd::force_target(target);
    TileContents got(whole, raster::DepthTest::kAlways);
    draw_simd(whole, 0, raster::DepthTest::kAlways, got);
    INFO(target);
    CHECK(test::untouched_outside(got.depth, 0, 0));
    CHECK(test::untouched_outside(got.primitive, 0, 0));
  }
}

}  // namespace
}  // namespace relief
