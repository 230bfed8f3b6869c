// The Highway kernels (simd/) against the scalar reference, on every target compiled in that
// this CPU can run, each forced in turn: every buffer bit-identical over a frame's grid or a
// soup of triangles, and the work counters equal. Targets this CPU cannot run are named (WARN),
// so a run on a machine without AVX-512 says that AVX3 was not checked there. The same kernels
// at awkward lengths: tests/simd/*_kernel_ranges_test.cc; whole frames:
// tests/simd/simd_frame_test.cc.
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/projected_domain.h"
#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "core/terrain_stages.h"
#include "core/vertex_transform.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "pipeline/tile_pass.h"
#include "raster/bins.h"
#include "raster/topology.h"
#include "simd/fbm.h"
#include "simd/projected_domain.h"
#include "simd/srgb.h"
#include "simd/surface.h"
#include "simd/targets.h"
#include "simd/vertex_transform.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

TEST_CASE("theTargetsCompiledInAreListedAndThoseThisCpuCannotRunAreNamed", "[simd]") {
  const EachTarget targets;
  const std::vector<simd::Target> compiled = simd::compiled_targets();
  REQUIRE_FALSE(compiled.empty());
  // A scalar fallback is always compiled in and always runs.
  CHECK(compiled.back().name == "SCALAR");
  CHECK(compiled.back().supported);
  if (!targets.skipped().empty()) {
    WARN("SIMD targets compiled in but not run on this CPU: " << targets.skipped());
  }
  // Highway 1.0.3 marks EMU128 broken on GCC before 12.3; SCALAR stands in for it.
  for (const simd::Target& t : compiled) {
    INFO(t.name);
    CHECK(t.name != "Unknown");
  }
}

TEST_CASE("forcingATargetThatIsUnknownOrThatThisCpuCannotRunIsRefused", "[simd]") {
  const EachTarget targets;
  CHECK_THROWS_WITH(simd::force_target("AVX9"),
                    Catch::Contains("unknown SIMD target \"AVX9\"; compiled in: "));
  for (const simd::Target& t : simd::compiled_targets()) {
    if (!t.supported) {
      CHECK_THROWS_WITH(simd::force_target(t.name), Catch::Contains("this CPU cannot run"));
    }
  }
  simd::force_target("scalar");  // names are case-insensitive
  CHECK(simd::current_target() == "SCALAR");
  simd::force_target("best");
  const simd::Target best = simd::compiled_targets().front();
  CHECK((simd::current_target() == best.name || !best.supported));
}

// Stage 3 of a frame's grid, scalar and SIMD, over an awkward range (not a multiple of any
// vector length) with the frame's mask, with no mask and with a random mask.
void check_fbm(const std::vector<std::string>& overrides, const EachTarget& targets) {
  const Scene scene = resolve_scene("default", overrides);
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> grid(plan.layout);
  run_terrain_stages(plan, grid);
  TerrainParams<float> params = make_terrain_params<float>(plan);
  choose_coordinate_forms(
      plan.terrain,
      octave_reach<float>(IndexRange{0, grid.layout.size()}, grid.dx, grid.dz, grid.nu, grid.valid),
      params.fbm);
  std::vector<std::uint8_t> random_mask(grid.layout.size());
  test::TestRandom random(5);
  for (std::uint8_t& m : random_mask) {
    m = random.uniform(0, 1) < 0.7 ? 1 : 0;
  }
  const IndexRange range{3, grid.layout.size() - 5};
  for (const std::span<const std::uint8_t> mask :
       {std::span<const std::uint8_t>(grid.valid), std::span<const std::uint8_t>(),
        std::span<const std::uint8_t>(random_mask)}) {
    std::vector<float> expected(grid.layout.size(), -1.0f);
    const FbmWork expected_work =
        evaluate_fbm<float>(params.fbm, lattice, range, grid.dx, grid.dz, grid.nu, mask, expected);
    for (const std::string& target : targets.runnable()) {
      simd::force_target(target);
      std::vector<float> got(grid.layout.size(), -1.0f);
      const FbmWork work =
          simd::evaluate_fbm(params.fbm, lattice, range, grid.dx, grid.dz, grid.nu, mask, got);
      INFO("target " << target << ", mask of " << mask.size());
      CHECK(test::same_bits<float>(got, expected));
      CHECK(work.points == expected_work.points);
      CHECK(work.octaves == expected_work.octaves);
    }
  }
}

TEST_CASE("simdFbmIsBitIdenticalToTheReferenceOnEveryTarget", "[simd]") {
  const EachTarget targets;
  const std::vector<std::string> small = {"grid.width=100", "grid.height=61"};
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {},
           {"terrain.warp.enabled=true"},
           {"terrain.interpolant=linear", "terrain.r=2.17"},
           {"terrain.interpolant=cubic", "terrain.lattice_size=4096"},
           // Fine octaves in the exact coordinate form (core/octave_coordinates.h).
           {"terrain.H=0.05", "terrain.last_octave=23"},
           {"terrain.H=0.05", "terrain.last_octave=23", "terrain.warp.enabled=true"},
           {"camera.position=[1e9, 700, -3e8]"}}) {
    std::vector<std::string> overrides = small;
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    INFO("overrides: " << (extra.empty() ? std::string("none") : extra.front()));
    check_fbm(overrides, targets);
  }
}

TEST_CASE("simdVertexTransformIsBitIdenticalToTheReferenceOnEveryTarget", "[simd]") {
  const EachTarget targets;
  TransformParams<float> t;
  test::TestRandom random(4);
  for (int c = 0; c < 3; ++c) {
    t.row_x[c] = float(random.uniform(-2, 2));
    t.row_y[c] = float(random.uniform(-2, 2));
    t.row_w[c] = float(random.uniform(-1, 1));
  }
  t.z_clip = 0.5f;
  const std::size_t count = 1000;
  std::vector<float> dx(count), dz(count), height(count);
  std::vector<std::uint8_t> need(count);
  for (std::size_t k = 0; k < count; ++k) {
    dx[k] = float(random.uniform(-1e4, 1e4));
    dz[k] = float(random.uniform(-1e4, 1e4));
    height[k] = float(random.uniform(-500, 500));
    need[k] = static_cast<std::uint8_t>(random.uniform(0, 4));  // kEvaluate | kDraw bits
  }
  const IndexRange range{5, count - 3};
  for (const std::span<const std::uint8_t> mask :
       {std::span<const std::uint8_t>(need), std::span<const std::uint8_t>()}) {
    std::vector<float> e[4], g[4];
    for (auto& v : e) {
      v.assign(count, -7.0f);
    }
    transform_vertices<float>(t, range, dx, dz, height, mask, {e[0], e[1], e[2], e[3]});
    for (const std::string& target : targets.runnable()) {
      simd::force_target(target);
      for (auto& v : g) {
        v.assign(count, -7.0f);
      }
      simd::transform_vertices(t, range, dx, dz, height, mask, {g[0], g[1], g[2], g[3]});
      INFO(target << ", mask of " << mask.size());
      for (int c = 0; c < 4; ++c) {
        CHECK(test::same_bits<float>(g[c], e[c]));
      }
    }
  }
}

TEST_CASE("simdSurfacePassIsBitIdenticalToTheReferenceOnEveryTarget", "[simd]") {
  const EachTarget targets;
  const Scene scene = resolve_scene("lake", {"grid.width=37", "grid.height=29"});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> grid(plan.layout);
  run_terrain_stages(plan, grid);
  const TerrainParams<float> params = make_terrain_params<float>(plan);
  // Holes in the grid and a random need mask: every neighbour case of core/surface.cc.
  test::TestRandom random(8);
  std::vector<std::uint8_t> valid(grid.valid.begin(), grid.valid.end());
  std::vector<std::uint8_t> need(valid.size());
  for (std::size_t k = 0; k < valid.size(); ++k) {
    valid[k] = valid[k] && random.uniform(0, 1) < 0.8 ? 1 : 0;
    need[k] = static_cast<std::uint8_t>(random.uniform(0, 4));
  }
  for (const bool with_need : {true, false}) {
    for (const RowRange rows : {RowRange{0, plan.layout.height}, RowRange{3, 11}}) {
      const SurfaceInputs<float> in{
          grid.dx, grid.dz, grid.height, valid,
          with_need ? std::span<const std::uint8_t>(need) : std::span<const std::uint8_t>()};
      GridBuffers<float> expected(plan.layout);
      surface_pass<float>(params.surface, rows, in, expected.surface());
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        GridBuffers<float> got(plan.layout);
        simd::surface_pass(params.surface, rows, in, got.surface());
        INFO(target << ", rows " << rows.begin << ".." << rows.end << ", need " << with_need);
        CHECK(test::same_bits<float>(got.nx, expected.nx));
        CHECK(test::same_bits<float>(got.ny, expected.ny));
        CHECK(test::same_bits<float>(got.nz, expected.nz));
        CHECK(test::same_bits<float>(got.slope, expected.slope));
        CHECK(test::same_bits<float>(got.water_depth, expected.water_depth));
      }
    }
  }
}

TEST_CASE("simdProjectedDomainIsBitIdenticalToTheReferenceOnEveryTarget", "[simd]") {
  const EachTarget targets;
  for (const std::vector<std::string>& overrides : std::vector<std::vector<std::string>>{
           {},
           {"camera.pitch_deg=-90"},
           {"camera.pitch_deg=25"},
           {"camera.pitch_deg=-0.5", "camera.fov_y_deg=120"},
           {"camera.position=[0, 20000, 0]", "camera.pitch_deg=-30"},
           {"camera.position=[5e8, 2, -3e8]", "camera.far=1e6"},
           {"terrain.lod.criterion=nyquist", "terrain.lod.bias=3"},
           {"terrain.lod.fractional=false", "terrain.lod.bias=0.37"}}) {
    std::vector<std::string> all = {"grid.width=83", "grid.height=47"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    const Scene scene = resolve_scene("default", all);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    const TerrainParams<float> params = make_terrain_params<float>(plan);
    const RowRange rows{0, plan.layout.height};
    GridBuffers<float> expected(plan.layout);
    project_domain<float>(params.domain, params.domain_rows, rows, expected.domain());
    for (const std::string& target : targets.runnable()) {
      simd::force_target(target);
      GridBuffers<float> got(plan.layout);
      simd::project_domain(params.domain, params.domain_rows, rows, got.domain());
      INFO(target << ", " << (overrides.empty() ? std::string("default") : overrides.front()));
      CHECK(test::same_bits<float>(got.dx, expected.dx));
      CHECK(test::same_bits<float>(got.dz, expected.dz));
      CHECK(test::same_bits<float>(got.sigma, expected.sigma));
      CHECK(test::same_bits<float>(got.nu, expected.nu));
      CHECK(std::equal(got.valid.begin(), got.valid.end(), expected.valid.begin()));
    }
  }
}

TEST_CASE("simdRasterInnerLoopIsBitIdenticalForEveryDepthTestOnEveryTarget", "[simd]") {
  const EachTarget targets;
  // Soups of overlapping triangles in front of the camera, with shared depths for the ties:
  // small ones (the 4 x 4 blocks of 32-bit lanes, moved inside the tile at its edges) and large
  // ones in a larger viewport (edge values at a block's origin beyond the 32-bit clamp, and
  // coefficients beyond the block path's limit: 64-bit rows).
  struct Soup {
    double min_size, max_size;
    int width, height;
  };
  const Soup soup = GENERATE(Soup{0.002, 0.3, 203, 131}, Soup{0.2, 1.5, 1000, 700});
  test::TestRandom random(12);
  const std::size_t count = 3000;
  std::vector<float> x, y, z, w;
  std::vector<std::uint32_t> indices;
  for (std::size_t t = 0; t < count; ++t) {
    const double cx = random.uniform(-1.2, 1.2), cy = random.uniform(-1.2, 1.2);
    const double size = random.uniform(soup.min_size, soup.max_size);
    const float depth = float(int(random.uniform(0, 8)) / 8.0);
    for (int v = 0; v < 3; ++v) {
      const float vw = float(random.uniform(1, 3));
      x.push_back(float((cx + random.uniform(-size, size)) * vw));
      y.push_back(float((cy + random.uniform(-size, size)) * vw));
      z.push_back(random.uniform(0, 1) < 0.5 ? depth * vw : float(random.uniform(0, 1)) * vw);
      w.push_back(vw);
      indices.push_back(static_cast<std::uint32_t>(indices.size()));
    }
  }
  for (const raster::DepthTest test :
       {raster::DepthTest::kGreater, raster::DepthTest::kGreaterEqual, raster::DepthTest::kLess,
        raster::DepthTest::kLessEqual, raster::DepthTest::kEqual, raster::DepthTest::kAlways,
        raster::DepthTest::kNever}) {
    raster::RasterState state;
    state.width = soup.width;
    state.height = soup.height;
    state.viewport = {0.0, 0.0, double(soup.width), double(soup.height)};
    state.cull = raster::CullMode::kNone;
    state.depth_test = test;
    state.depth_clear = test == raster::DepthTest::kGreater ? 0.0f : 0.5f;
    const raster::TriangleSetup setup(state);
    const raster::TileGrid tiles = raster::make_tile_grid(state);
    std::vector<raster::SetupChunk> chunks(1);
    raster::setup_chunk(setup, raster::ClipVertices{x, y, z, w}, raster::IndexedTriangles{indices},
                        0, chunks[0]);
    raster::bin_chunk(chunks[0], tiles);
    for (int tile = 0; tile < tiles.count(); ++tile) {
      raster::TileVisibility expected, got;
      raster::rasterize_tile(chunks, tiles, tile, state, expected);
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        rasterize_tile_simd(chunks, tiles, tile, state, got);
        INFO(target << ", depth test " << int(test) << ", tile " << tile);
        REQUIRE(std::memcmp(got.depth, expected.depth, sizeof(got.depth)) == 0);
        REQUIRE(std::memcmp(got.primitive, expected.primitive, sizeof(got.primitive)) == 0);
      }
    }
  }
}

// srgb_byte's own search (core/srgb.h), as the scalar frame runs it: the specification.
TEST_CASE("everySrgbBucketSpansAtMostTwoCodesSoOneStepFindsTheCode", "[simd]") {
  const auto& points = srgb_detail::decision_points();
  const auto& steps = srgb_detail::bucket_steps();
  for (std::uint32_t bucket = 0; bucket < 0x3f80; ++bucket) {
    // The bucket's largest float is below the decision point after the next one.
    const float largest = std::bit_cast<float>((bucket << 16) | 0xffffu);
    const int code = steps.code[bucket];
    INFO("bucket " << bucket);
    if (code + 1 < 255) {
      REQUIRE(double(largest) < points[code + 1]);
    }
    if (code < 255) {
      REQUIRE(double(steps.next_at[bucket]) >= points[code]);
      REQUIRE(double(std::nextafter(steps.next_at[bucket], 0.0f)) < points[code]);
    }
  }
}

TEST_CASE("simdSrgbEncodingIsSrgbByteOnEveryTarget", "[simd]") {
  const EachTarget targets;
  std::vector<float> values = {0.0f,
                               -0.0f,
                               1.0f,
                               -1.0f,
                               0.5f,
                               1e-45f,
                               1e-38f,
                               3e38f,
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(),
                               std::nanf(""),
                               std::nextafter(1.0f, 0.0f),
                               std::nextafter(0.0f, 1.0f)};
  // Every decision point and its neighbours, every bucket's edges, and random values.
  for (const double t : srgb_detail::decision_points()) {
    const float f = float(t);
    for (float v = std::nextafter(std::nextafter(f, 0.0f), 0.0f),
               end = std::nextafter(std::nextafter(f, 2.0f), 2.0f);
         v <= end; v = std::nextafter(v, 2.0f)) {
      values.push_back(v);
    }
  }
  for (std::uint32_t bucket = 0; bucket < 0x3f81; ++bucket) {
    values.push_back(std::bit_cast<float>(bucket << 16));
    values.push_back(std::bit_cast<float>((bucket << 16) | 0xffffu));
  }
  test::TestRandom random(9);
  for (int k = 0; k < 100000; ++k) {
    values.push_back(float(random.uniform(-0.1, 1.1)));
  }
  std::vector<std::uint8_t> expected(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    expected[k] = srgb_byte(values[k]);
  }
  for (const std::string& target : targets.runnable()) {
    simd::force_target(target);
    // Awkward lengths and offsets: the tail of a vector, an unaligned start.
    for (const std::size_t offset : {std::size_t(0), std::size_t(3)}) {
      std::vector<std::uint8_t> got(values.size() - offset, 7);
      simd::encode_srgb(std::span<const float>(values).subspan(offset), got);
      INFO("target " << target << ", offset " << offset);
      CHECK(std::equal(got.begin(), got.end(), expected.begin() + std::ptrdiff_t(offset)));
    }
  }
}

}  // namespace
}  // namespace relief
