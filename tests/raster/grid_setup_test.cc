// setup_chunk for the grid (vertices prepared once per chunk, raster/triangle_setup.h) must
// give exactly what setup_clip gives triangle by triangle: the same records, in the same order,
// the same counts, and bin_entries the tiles their boxes touch; and so must an index list's
// set-up from vertices prepared once per frame in blocks (setup_indexed_chunk).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/counter_hash.h"
#include "raster/bins.h"
#include "raster/triangle_setup.h"

namespace relief::raster {
namespace {

bool same_record(const RasterTriangle& a, const RasterTriangle& b) {
  for (int i = 0; i < 3; ++i) {
    if (a.c[i] != b.c[i] || a.a[i] != b.a[i] || a.b[i] != b.b[i]) {
      return false;
    }
  }
  return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1 &&
         std::memcmp(&a.z0, &b.z0, sizeof(double)) == 0 &&
         std::memcmp(&a.dzdx, &b.dzdx, sizeof(double)) == 0 &&
         std::memcmp(&a.dzdy, &b.dzdy, sizeof(double)) == 0 && a.primitive == b.primitive;
}

TEST_CASE("gridSetupGivesSetupClipsTrianglesBitForBit", "[raster]") {
  // A 150 x 70 grid seen in perspective across the near plane and the guard band, with
  // vertices on the planes, behind the eye, at the origin, non-finite and denormal.
  const int width = 150, height = 70;
  const GridLayout layout = make_grid_layout(width, height);
  std::vector<float> x(layout.size()), y(layout.size()), z(layout.size()), w(layout.size());
  std::vector<std::uint8_t> valid(layout.size()), need(layout.size());
  std::uint64_t counter = 0;
  const auto uniform = [&counter] {  // [0, 1)
    return double(mix64(++counter + kGoldenGamma) >> 11) * 0x1.0p-53;
  };
  // The guard factor of the first viewport below (TriangleSetup's), for vertices on and
  // around the guard planes and half of them.
  const float guard = static_cast<float>((kGuardBandPixels - 100.0f) / 100.0f);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const std::size_t k = layout.index(i, j);
      const double vw = std::exp(-4.0 + 12.0 * (j + uniform()) / height);
      const double nx = -1.5 + 3.0 * (i + 0.3 * uniform()) / width;
      const double ny = -1.5 + 3.0 * uniform();
      w[k] = float(vw);
      x[k] = float(nx * vw);
      y[k] = float(ny * vw);
      z[k] = float(0.1);
      switch (mix64(++counter) % 40) {
        case 0:
          w[k] = -w[k];
          break;
        case 1:
          z[k] = w[k];
          break;
        case 2:
          z[k] = std::nextafter(w[k], 0.0f);
          break;
        case 3:
          z[k] = 0.0f;
          break;
        case 4:
          x[k] = guard * w[k];
          break;
        case 5:
          x[k] = -std::nextafter(guard * w[k], 1e30f);
          break;
        case 6:
          x[k] = std::nextafter(float(double(guard) * w[k]), 0.0f);
          break;
        case 13:
          y[k] = 0.5f * (guard * w[k]);
          break;
        case 14:
          y[k] = std::nextafter(0.5f * (guard * w[k]), 1e30f);
          break;
        case 7:
          x[k] = 1e5f * w[k];
          break;
        case 8:
          x[k] = y[k] = z[k] = w[k] = 0.0f;
          break;
        case 9:
          x[k] = std::numeric_limits<float>::denorm_min();
          break;
        case 10:
          y[k] = std::numeric_limits<float>::infinity();
          break;
        case 11:
          w[k] = std::numeric_limits<float>::quiet_NaN();
          break;
        case 12:
          w[k] = 1e-37f;
          break;
        default:
          break;
      }
      valid[k] = mix64(++counter) % 50 != 0;
      need[k] = mix64(++counter) % 10 == 0 ? 1 : 3;
    }
  }
  // Triangles (a, b, c) whose vertices are collinear in clip space (c the midpoint of a and b,
  // exact) but not after snapping: their depth plane is undefined (set-up's constant-depth
  // fallback).
  for (int j = 2; j + 1 < height; j += 5) {
    for (int i = 3; i + 1 < width; i += 7) {
      const std::size_t a = layout.index(i, j), b = layout.index(i + 1, j),
                        c = layout.index(i + 1, j + 1);
      const float xa = float(i % 13 - 6), xb = float(5 + 2 * (i % 4));
      x[a] = xa, y[a] = 0.0f, z[a] = 1.0f, w[a] = 8.0f;
      x[b] = xb, y[b] = 6.0f, z[b] = 3.0f, w[b] = 24.0f;
      x[c] = 0.5f * (xa + xb), y[c] = 3.0f, z[c] = 2.0f, w[c] = 16.0f;
    }
  }
  const ClipVertices vertices{x, y, z, w};
  for (const bool with_need : {false, true}) {
    const GridTriangles grid{
        layout, valid,
        with_need ? std::span<const std::uint8_t>(need) : std::span<const std::uint8_t>()};
    for (const CullMode cull : {CullMode::kNone, CullMode::kBack, CullMode::kFront}) {
      for (const Viewport viewport : {Viewport{0, 0, 200, 160}, Viewport{-37.5, 20.25, 300, 90}}) {
        RasterState state;
        state.width = 200;
        state.height = 160;
        state.viewport = viewport;
        state.cull = cull;
        const TriangleSetup setup(state);
        std::uint64_t set_up = 0;
        for (std::size_t chunk = 0; chunk < setup_chunk_count(grid.count()); ++chunk) {
          SetupChunk got;
          setup_chunk(setup, vertices, grid, chunk, got);
          std::vector<RasterTriangle> expected;
          std::uint32_t submitted = 0;
          const auto begin = static_cast<std::uint32_t>(chunk * kSetupChunk);
          const auto end = std::min<std::uint32_t>(grid.count(), begin + kSetupChunk);
          for (std::uint32_t t = begin; t < end; ++t) {
            std::uint32_t v[3];
            if (grid.vertices(t, v)) {
              ++submitted;
              const ClipVertex clip[3] = {{x[v[0]], y[v[0]], z[v[0]], w[v[0]]},
                                          {x[v[1]], y[v[1]], z[v[1]], w[v[1]]},
                                          {x[v[2]], y[v[2]], z[v[2]], w[v[2]]}};
              setup.setup_clip(t, clip, expected);
            }
          }
          INFO("chunk " << chunk << ", cull " << int(cull) << ", need " << with_need);
          REQUIRE(got.submitted == submitted);
          REQUIRE(got.triangles.size() == expected.size());
          std::uint64_t entries = 0;
          for (std::size_t k = 0; k < expected.size(); ++k) {
            REQUIRE(same_record(got.triangles[k], expected[k]));
            const RasterTriangle& t = expected[k];
            entries += std::uint64_t(t.x1 / kTileSize - t.x0 / kTileSize + 1) *
                       std::uint64_t(t.y1 / kTileSize - t.y0 / kTileSize + 1);
          }
          REQUIRE(got.bin_entries == entries);
          set_up += expected.size();
        }
        CHECK(set_up > 1000);  // the set exercises the common path
      }
    }
  }
  // The same vertices as an index list (a GeoMipMap mesh's path): the grid's triangles in a
  // scrambled order, so that a chunk reads vertices far apart, from blocks of 1024 prepared
  // vertices, against the per-triangle set-up of setup_chunk<IndexedTriangles>.
  std::vector<std::uint32_t> indices;
  const GridTriangles all{layout, valid};
  const std::uint32_t count = all.count();
  for (std::uint32_t n = 0; n < count; ++n) {
    const std::uint32_t t = static_cast<std::uint32_t>((std::uint64_t(n) * 7919u) % count);
    std::uint32_t v[3];
    all.vertices(t, v);  // invalid corners too: an index list has no validity
    indices.insert(indices.end(), {v[0], v[1], v[2]});
  }
  REQUIRE(count % 7919u != 0);  // 7919 is prime: n -> 7919 n mod count is a permutation
  const IndexedTriangles mesh{indices};
  const std::size_t block = 1024;
  for (const CullMode cull : {CullMode::kNone, CullMode::kBack}) {
    RasterState state;
    state.width = 200;
    state.height = 160;
    state.viewport = Viewport{0, 0, 200, 160};
    state.cull = cull;
    const TriangleSetup setup(state);
    std::vector<PreparedVertices> blocks((layout.size() + block - 1) / block);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      setup.prepare_vertices(vertices, b * block, std::min(layout.size(), (b + 1) * block), {}, {},
                             blocks[b]);
    }
    std::uint64_t set_up = 0;
    for (std::size_t chunk = 0; chunk < setup_chunk_count(mesh.count()); ++chunk) {
      SetupChunk got, expected;
      setup_indexed_chunk(setup, vertices, mesh, blocks, block, chunk, got);
      setup_chunk(setup, vertices, mesh, chunk, expected);
      INFO("indexed chunk " << chunk << ", cull " << int(cull));
      REQUIRE(got.submitted == expected.submitted);
      REQUIRE(got.triangles.size() == expected.triangles.size());
      for (std::size_t k = 0; k < expected.triangles.size(); ++k) {
        REQUIRE(same_record(got.triangles[k], expected.triangles[k]));
      }
      REQUIRE(got.bin_entries == expected.bin_entries);
      set_up += expected.triangles.size();
    }
    CHECK(set_up > 1000);
  }
}

}  // namespace
}  // namespace relief::raster
