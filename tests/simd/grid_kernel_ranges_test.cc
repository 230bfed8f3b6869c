// The Highway kernels that run over whole grid rows (simd/projected_domain.h, the plane's and
// the planet's; simd/vertex_outcodes.h, simd/surface.h) on grids of every awkward width
// (tests/simd/kernel_ranges.h) on every target this CPU runs: every entry of the rows in range,
// the row padding included, is the scalar stage's (core/projected_domain.h,
// core/planet_domain.h, core/vertex_culling.h, core/surface.h) bit for bit, and no entry of
// another row is written.
// A row starts at a multiple of the pitch (16 floats, core/grid_buffers.h), so the unaligned
// starts of the element-wise kernels have no counterpart here: the ranges start at row 0 and
// inside the grid instead, and hold no row, one row or several.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/lattice.h"
#include "core/planet_domain.h"
#include "core/projected_domain.h"
#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "core/surface.h"
#include "core/terrain_stages.h"
#include "core/vertex_culling.h"
#include "simd/projected_domain.h"
#include "simd/surface.h"
#include "simd/targets.h"
#include "simd/vertex_outcodes.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kGridRows = 6;

// The rows tried on every width: none, the first, one inside, and all but the border rows.
const RowRange kRowRanges[] = {{2, 2}, {0, 1}, {3, 4}, {1, kGridRows - 1}};

// A frame of the lake (water, so stage 4 computes depths) on a grid 53 vertices wide, the
// widest tried; narrower grids take the first columns of its rows. The kernels read the width
// and pitch from their parameter structs, so a narrower grid is the same parameters with
// those two changed.
struct WideFrame {
  Scene scene = resolve_scene("lake", {"grid.width=53", "grid.height=6"});
  NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  FramePlan plan = make_frame_plan(scene, lattice);  // points at `lattice`: not copyable
  TerrainParams<float> params = make_terrain_params<float>(plan);
  GridBuffers<float> grid{plan.layout};

  WideFrame() { run_terrain_stages(plan, grid); }
  WideFrame(const WideFrame&) = delete;
  WideFrame& operator=(const WideFrame&) = delete;
};

// Stage 2-3 buffers of the first `width` columns, laid out for that width (padding: invalid,
// zeros), with kGuardElements after the last row.
struct NarrowGrid {
  GridLayout layout;
  std::vector<float> dx, dz, height;
  std::vector<std::uint8_t> valid, need;
};

NarrowGrid narrow_grid(const GridBuffers<float>& wide, int width) {
  NarrowGrid g;
  g.layout = make_grid_layout(width, wide.layout.height);
  const std::size_t size = g.layout.size() + test::kGuardElements;
  g.dx.assign(size, 0.0f);
  g.dz.assign(size, 0.0f);
  g.height.assign(size, 0.0f);
  g.valid.assign(size, 0);
  g.need.assign(size, 0);
  test::TestRandom random(53);
  for (int j = 0; j < g.layout.height; ++j) {
    for (int i = 0; i < width; ++i) {
      const std::size_t from = wide.layout.index(i, j), to = g.layout.index(i, j);
      g.dx[to] = wide.dx[from];
      g.dz[to] = wide.dz[from];
      g.height[to] = wide.height[from];
      // Holes among the valid vertices and every need: each neighbour case of stage 4.
      g.valid[to] = wide.valid[from] && random.uniform(0, 1) < 0.85 ? 1 : 0;
      g.need[to] = static_cast<std::uint8_t>(random.uniform(0, 4));
    }
  }
  return g;
}

// The buffer indices of a row range.
std::size_t first_of(const GridLayout& layout, RowRange rows) {
  return layout.index(0, rows.begin);
}
std::size_t end_of(const GridLayout& layout, RowRange rows) {
  return layout.index(0, rows.end);
}

// Stage 2's five outputs, all holding the sentinel.
struct DomainOutputs {
  std::vector<float> dx, dz, sigma, nu;
  std::vector<std::uint8_t> valid;

  explicit DomainOutputs(std::size_t size)
      : dx(size, test::sentinel<float>()),
        dz(size, test::sentinel<float>()),
        sigma(size, test::sentinel<float>()),
        nu(size, test::sentinel<float>()),
        valid(size, test::sentinel<std::uint8_t>()) {}
  DomainSpans<float> spans() { return {dx, dz, sigma, nu, valid}; }
};

// Stage 2 at every awkward width and row range: `scalar(params, rows, spans)` and
// `highway(params, rows, spans)` (the plane's or the sphere's, over `wide`'s parameters with
// the width and pitch changed) write the same bits, only in their rows, on every target.
template <class Scalar, class Highway>
void check_domain_kernel(const DomainParams<float>& wide, const Scalar& scalar,
                         const Highway& highway) {
  const EachTarget targets;
  for (const std::size_t width : test::awkward_lengths()) {
    const GridLayout layout = make_grid_layout(int(width), kGridRows);
    DomainParams<float> params = wide;
    params.width = layout.width;
    params.pitch = layout.pitch;
    for (const RowRange rows : kRowRanges) {
      const std::size_t size = layout.size() + test::kGuardElements;
      DomainOutputs expected(size);
      scalar(params, rows, expected.spans());
      const std::size_t begin = first_of(layout, rows), end = end_of(layout, rows);
      INFO("width " << width << ", rows " << rows.begin << " to " << rows.end);
      REQUIRE(test::untouched_outside(expected.nu, begin, end));
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        DomainOutputs got(size);
        highway(params, rows, got.spans());
        INFO(target);
        CHECK(test::same_bits(got.dx, expected.dx));
        CHECK(test::same_bits(got.dz, expected.dz));
        CHECK(test::same_bits(got.sigma, expected.sigma));
        CHECK(test::same_bits(got.nu, expected.nu));
        CHECK(test::same_bits(got.valid, expected.valid));
      }
    }
  }
}

TEST_CASE("simdProjectedDomainOnAwkwardWidthsIsTheScalarStageAndWritesOnlyItsRows", "[simd]") {
  const WideFrame frame;
  const DomainRows<float>& table = frame.params.domain_rows;
  check_domain_kernel(
      frame.params.domain,
      [&](const DomainParams<float>& p, RowRange rows, DomainSpans<float> out) {
        project_domain<float>(p, table, rows, out);
      },
      [&](const DomainParams<float>& p, RowRange rows, DomainSpans<float> out) {
        simd::project_domain(p, table, rows, out);
      });
}

TEST_CASE("simdPlanetDomainOnAwkwardWidthsIsTheScalarStageAndWritesOnlyItsRows", "[simd]") {
  // From orbit (equal angles), near the surface looking at the horizon (the plain hit with
  // the grid sphere, rays that miss it), and inside the blend's band (equal_angle from 20 to
  // 200 km: a missing ray's limb angle blended in), at the horizon and straight down.
  for (const std::vector<std::string>& view :
       {std::vector<std::string>{"camera.position=[0, 2000100, 0]"},
        std::vector<std::string>{"camera.position=[0, 700, 0]", "camera.pitch_deg=0"},
        std::vector<std::string>{"camera.position=[0, 60000, 0]", "camera.pitch_deg=0"},
        std::vector<std::string>{"camera.position=[0, 60000, 0]", "camera.pitch_deg=-90"}}) {
    std::vector<std::string> overrides = {"grid.width=53", "grid.height=6"};
    overrides.insert(overrides.end(), view.begin(), view.end());
    const Scene scene = resolve_scene("planet", overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    const TerrainParams<float> frame = make_terrain_params<float>(plan);
    INFO(view.front() << " " << view.back());
    check_domain_kernel(
        frame.domain,
        [&](const DomainParams<float>& p, RowRange rows, DomainSpans<float> out) {
          project_planet_domain<float>(p, frame.planet, frame.domain_rows, rows, out);
        },
        [&](const DomainParams<float>& p, RowRange rows, DomainSpans<float> out) {
          simd::project_planet_domain(p, frame.planet, frame.domain_rows, rows, out);
        });
  }
}

TEST_CASE("simdVertexOutcodesOnAwkwardWidthsAreTheScalarOutcodesAndWriteOnlyTheirRows", "[simd]") {
  const EachTarget targets;
  const WideFrame frame;
  const CullParams<float> wide_params = make_cull_params<float>(frame.plan);
  for (const std::size_t width : test::awkward_lengths()) {
    const NarrowGrid g = narrow_grid(frame.grid, int(width));
    CullParams<float> params = wide_params;
    params.width = g.layout.width;
    params.pitch = g.layout.pitch;
    // Of the height bounds' segments (before stage 3) and of the vertices' own heights.
    for (const bool own_heights : {false, true}) {
      const std::span<const float> height =
          own_heights ? std::span<const float>(g.height) : std::span<const float>();
      for (const RowRange rows : kRowRanges) {
        const std::size_t size = g.layout.size() + test::kGuardElements;
        std::vector<std::uint8_t> expected(size, test::sentinel<std::uint8_t>());
        vertex_outcodes<float>(params, rows, g.dx, g.dz, height, g.valid, expected);
        const std::size_t begin = first_of(g.layout, rows), end = end_of(g.layout, rows);
        INFO("width " << width << ", own heights " << own_heights << ", rows " << rows.begin
                      << " to " << rows.end);
        REQUIRE(test::untouched_outside(expected, begin, end));
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          std::vector<std::uint8_t> got(size, test::sentinel<std::uint8_t>());
          simd::vertex_outcodes(params, rows, g.dx, g.dz, height, g.valid, got);
          INFO(target);
          CHECK(test::same_bits(got, expected));
        }
      }
    }
  }
}

// Stage 4's five outputs, all holding the sentinel.
struct SurfaceOutputs {
  std::vector<float> nx, ny, nz, slope, water_depth;

  explicit SurfaceOutputs(std::size_t size)
      : nx(size, test::sentinel<float>()),
        ny(size, test::sentinel<float>()),
        nz(size, test::sentinel<float>()),
        slope(size, test::sentinel<float>()),
        water_depth(size, test::sentinel<float>()) {}
  SurfaceSpans<float> spans() { return {nx, ny, nz, slope, water_depth}; }
};

TEST_CASE("simdSurfacePassOnAwkwardWidthsIsTheScalarPassAndWritesOnlyItsRows", "[simd]") {
  const EachTarget targets;
  const WideFrame frame;
  REQUIRE(frame.params.surface.water_enabled != 0);  // the depths are computed, not zeros
  for (const std::size_t width : test::awkward_lengths()) {
    const NarrowGrid g = narrow_grid(frame.grid, int(width));
    SurfaceParams<float> params = frame.params.surface;
    params.width = g.layout.width;
    params.pitch = g.layout.pitch;
    for (const bool with_need : {false, true}) {
      const SurfaceInputs<float> in{
          g.dx, g.dz, g.height, g.valid,
          with_need ? std::span<const std::uint8_t>(g.need) : std::span<const std::uint8_t>()};
      for (const RowRange rows : kRowRanges) {
        const std::size_t size = g.layout.size() + test::kGuardElements;
        SurfaceOutputs expected(size);
        surface_pass<float>(params, rows, in, expected.spans());
        const std::size_t begin = first_of(g.layout, rows), end = end_of(g.layout, rows);
        INFO("width " << width << ", need " << with_need << ", rows " << rows.begin << " to "
                      << rows.end);
        REQUIRE(test::untouched_outside(expected.nx, begin, end));
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          SurfaceOutputs got(size);
          simd::surface_pass(params, rows, in, got.spans());
          INFO(target);
          CHECK(test::same_bits(got.nx, expected.nx));
          CHECK(test::same_bits(got.ny, expected.ny));
          CHECK(test::same_bits(got.nz, expected.nz));
          CHECK(test::same_bits(got.slope, expected.slope));
          CHECK(test::same_bits(got.water_depth, expected.water_depth));
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
