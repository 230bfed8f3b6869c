// The projector spends the grid on what can be seen (§4.1, Figure 5; projector.h): the
// regional height bound it rests on is never exceeded, the grid's triangles mostly reach the
// image, and the refinement loses no terrain the global slab's projector drew.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_bound_pyramid.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "pipeline/cpu_backend.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

struct Variant {
  std::string preset;
  std::vector<std::string> overrides;
};

// Unwarped and warped terrains, every interpolant, a non-integer lacunarity (no period), a
// first octave above 0, shifted octaves (t0) and a camera far out.
std::vector<Variant> bound_variants() {
  return {
      {"default", {}},
      {"plain", {"terrain.interpolant=linear"}},
      {"plain", {"terrain.interpolant=cubic", "terrain.r=2.17", "terrain.H=0.6"}},
      {"plain", {"terrain.first_octave=2", "terrain.last_octave=12", "terrain.lattice_size=16"}},
      {"plain", {"terrain.warp.t0=[0.3, -1.7]"}},
      {"lava", {}},
      {"dunes", {}},
      {"lava", {"terrain.warp.c3=[2.5, -1.5]", "terrain.warp.t0=[0.5, 0.25]"}},
      {"default", {"camera.position=[1000000, 700, -2500000]"}}};
}

TEST_CASE("regionalHeightBoundHoldsAtEveryPointOfItsRegion", "[projector]") {
  test::TestRandom random(7);
  for (const Variant& v : bound_variants()) {
    const Scene scene = resolve_scene(v.preset, v.overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    const LatticeRangePyramid pyramid = make_lattice_range_pyramid(lattice);
    const RegionalHeightBound regional(plan.terrain, pyramid);
    const ValueRange global = regional.global();
    const double nu_max = plan.lod.nu_max;
    INFO(v.preset << " " << (v.overrides.empty() ? "" : v.overrides.front()));
    for (int region = 0; region < 150; ++region) {
      // Regions from a tenth of a unit to 10 km, anywhere within 30 km of the camera.
      const double half = std::pow(10.0, random.uniform(-1.0, 4.0));
      const double cx = random.uniform(-30000.0, 30000.0);
      const double cz = random.uniform(-30000.0, 30000.0);
      const ValueRange h = regional.bound(cx - half, cx + half, cz - half, cz + half);
      REQUIRE(h.lo >= global.lo);
      REQUIRE(h.hi <= global.hi);
      for (int k = 0; k < 12; ++k) {
        // Float points inside the region (the stage's inputs are floats), any octave count.
        const auto x = static_cast<float>(cx + half * random.uniform(-1.0, 1.0));
        const auto z = static_cast<float>(cz + half * random.uniform(-1.0, 1.0));
        if (std::abs(x - cx) > half || std::abs(z - cz) > half) {
          continue;
        }
        const double nu = k == 0 ? nu_max : random.uniform(1.0, nu_max);
        const double hd = fbm_height<double>(plan.terrain, x, z, nu);
        const float hf = fbm_height<float>(plan.terrain, x, z, static_cast<float>(nu));
        INFO("region centre " << cx << ", " << cz << " half " << half << ": nu " << nu);
        REQUIRE(hd >= h.lo);
        REQUIRE(hd <= h.hi);
        REQUIRE(double(hf) >= h.lo);
        REQUIRE(double(hf) <= h.hi);
      }
    }
  }
}

TEST_CASE("regionalHeightBoundIsMuchTighterThanTheGlobalSlabOverSmallRegions", "[projector]") {
  for (const std::string& preset : {std::string("default"), std::string("lava")}) {
    const Scene scene = resolve_scene(preset, {});
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    const LatticeRangePyramid pyramid = make_lattice_range_pyramid(lattice);
    const RegionalHeightBound regional(plan.terrain, pyramid);
    const ValueRange global = regional.global();
    const ValueRange h = regional.bound(-50.0, 50.0, 450.0, 550.0);
    INFO(preset << ": global " << global.lo << " .. " << global.hi << ", 100 x 100 region " << h.lo
                << " .. " << h.hi << " (camera-relative)");
    CHECK(h.hi - h.lo < 0.2 * (global.hi - global.lo));
  }
}

TEST_CASE("latticeRangePyramidCoversEveryIndexRangeAndScansSmallOnesExactly", "[projector]") {
  test::TestRandom random(11);
  for (const int size : {4, 16, 256, 1024}) {
    const NoiseLattice lattice = make_noise_lattice(3, size);
    const LatticeRangePyramid pyramid = make_lattice_range_pyramid(lattice);
    for (int trial = 0; trial < 300; ++trial) {
      const auto i0 =
          static_cast<std::int64_t>(std::floor(random.uniform(-3.0 * size, 3.0 * size)));
      const auto j0 =
          static_cast<std::int64_t>(std::floor(random.uniform(-3.0 * size, 3.0 * size)));
      const auto ni = static_cast<std::int64_t>(std::pow(2.0, random.uniform(0.0, 11.0)));
      const auto nj = trial % 3 == 0 ? ni : static_cast<std::int64_t>(random.uniform(1.0, 6.0));
      double lo = 1e300, hi = -1e300;
      for (std::int64_t j = j0; j < j0 + std::min<std::int64_t>(nj, size); ++j) {
        for (std::int64_t i = i0; i < i0 + std::min<std::int64_t>(ni, size); ++i) {
          const float v =
              lattice.at(static_cast<int>(i & (size - 1)), static_cast<int>(j & (size - 1)));
          lo = std::min(lo, double(v));
          hi = std::max(hi, double(v));
        }
      }
      const ValueRange r = lattice_range(pyramid, lattice, i0, ni, j0, nj);
      INFO("P " << size << " range " << i0 << " + " << ni << ", " << j0 << " + " << nj);
      REQUIRE(r.lo <= lo);
      REQUIRE(r.hi >= hi);
      if (ni * nj <= 16 && ni < size && nj < size) {
        REQUIRE(r.lo == lo);
        REQUIRE(r.hi == hi);
      }
    }
  }
}

TEST_CASE("mostTrianglesOfTheDefaultFrameAreSetUp", "[projector]") {
  // The old projector set up 122,263 of 522,242 (23%): half the grid lay below the screen.
  // What remains are back faces (about a fifth of the grid: the slopes facing away), the rows
  // whose terrain is nearer on one side of the image than on the other (a projected grid's
  // rows run parallel to the camera's right axis), and the bound's looseness.
  const Scene scene = resolve_scene("default", {});
  const SceneResources resources = load_scene_resources(scene);
  const Frame frame = render_frame(scene, resources, FrameRequest{});
  const double share = double(frame.stats.raster.setup) / double(frame.stats.raster.triangles);
  CHECK(share > 0.40);  // measured: 46%
}

// The visibility buffer of a plan's grid, rendered outside the pipeline (stages 2-4 of the
// reference, then the clip transform in double and the rasteriser), so that a plan with the
// global slab's projector can be drawn beside the frame's.
raster::VisibilityBuffer draw(const Scene& scene, const FramePlan& plan) {
  GridBuffers<float> b(plan.layout);
  run_terrain_stages(plan, b);
  const std::size_t n = plan.layout.size();
  std::vector<float> x(n), y(n), z(n), w(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double p[3] = {b.dx[k], b.height[k], b.dz[k]};
    double cx = 0, cy = 0, cw = 0;
    for (int c = 0; c < 3; ++c) {
      cx += plan.clip.row_x[c] * p[c];
      cy += plan.clip.row_y[c] * p[c];
      cw += plan.clip.row_w[c] * p[c];
    }
    x[k] = float(cx);
    y[k] = float(cy);
    z[k] = float(plan.clip.z_clip);
    w[k] = float(cw);
  }
  raster::VisibilityBuffer out;
  raster::rasterize(frame_raster_state(scene), raster::ClipVertices{x, y, z, w},
                    raster::GridTriangles{plan.layout, b.valid}, out);
  return out;
}

std::vector<Variant> camera_variants() {
  const std::vector<std::string> small = {"viewport.width=240", "viewport.height=192",
                                          "grid.width=128", "grid.height=128"};
  std::vector<Variant> list;
  for (const char* preset : {"default", "lava", "dunes", "lake", "plain"}) {
    list.push_back({preset, small});
  }
  const std::vector<std::vector<std::string>> cameras = {
      {"camera.position=[0, 12000, 0]", "camera.pitch_deg=-60"},
      {"camera.position=[0, 12000, 0]", "camera.pitch_deg=-90"},
      {"camera.position=[0, 120, 0]", "camera.pitch_deg=-5"},
      {"camera.position=[600000, 700, -800000]"},
      {"camera.position=[0, 1000000, 0]", "camera.pitch_deg=-90", "camera.far=1000000000"}};
  for (const auto& camera : cameras) {
    list.push_back({"default", small});
    list.back().overrides.insert(list.back().overrides.end(), camera.begin(), camera.end());
  }
  return list;
}

// The global slab's projector (make_projector without a terrain: the polytope of before the
// refinement, its rows spanned the same way) beside the frame's, for the presets and the
// cameras of the issue: high above looking down, just above the terrain, far from the origin.
TEST_CASE("refinedProjectorDrawsTheTerrainWhereTheGlobalSlabsProjectorDid", "[projector]") {
  for (const Variant& v : camera_variants()) {
    const Scene scene = resolve_scene(v.preset, v.overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan refined = make_frame_plan(scene, lattice);
    FramePlan global = refined;
    global.projector = make_projector(global.camera, global.bounds, scene.terrain.base_height);
    global.screen = make_screen_grid(scene.grid, global.projector);
    const raster::VisibilityBuffer a = draw(scene, global);
    const raster::VisibilityBuffer b = draw(scene, refined);
    INFO(v.preset << " " << v.overrides.back());
    int covered_a = 0, covered_b = 0, bottom_lost = 0;
    for (std::size_t k = 0; k < a.primitive.size(); ++k) {
      covered_a += a.primitive[k] != raster::kNoPrimitive;
      covered_b += b.primitive[k] != raster::kNoPrimitive;
    }
    for (int px = 0; px < a.width; ++px) {
      bottom_lost += a.primitive[a.index(px, 0)] != raster::kNoPrimitive &&
                     b.primitive[b.index(px, 0)] == raster::kNoPrimitive;
    }
    // The bottom row keeps every terrain pixel; elsewhere the silhouettes move by the
    // sampling (the refined grid is denser), so coverage agrees to a percent of the image.
    CHECK(bottom_lost == 0);
    CHECK(std::abs(covered_a - covered_b) <= a.width * a.height / 100);
  }
}

// The refinement's rows run in any order, on any thread (core/projector.h, ParallelRows), and
// the projector equals the serial loop's, member by member (the fit reads extremes and a
// sorted hull, so this checks the rows' outputs and their isolation, not their join order).
TEST_CASE("theRefinedProjectorIsTheSameWhateverOrderItsRowsRunIn", "[projector]") {
  const auto same = [](const Projector& a, const Projector& b) {
    const auto components = [](const glm::dvec3& v) {
      return std::array<double, 3>{v.x, v.y, v.z};
    };
    bool hull = a.hull.size() == b.hull.size();
    for (std::size_t k = 0; hull && k < a.hull.size(); ++k) {
      hull = a.hull[k] == b.hull[k];
    }
    return a.terrain_visible == b.terrain_visible &&
           components(a.forward) == components(b.forward) &&
           components(a.right) == components(b.right) && components(a.up) == components(b.up) &&
           a.height_above_plane == b.height_above_plane && a.coverage.x0 == b.coverage.x0 &&
           a.coverage.x1 == b.coverage.x1 && a.coverage.y0 == b.coverage.y0 &&
           a.coverage.y1 == b.coverage.y1 && hull &&
           a.max_footprint_distance == b.max_footprint_distance;
  };
  int rows_seen = 0;
  const ParallelRows backwards = [&](int count, const std::function<void(int)>& body) {
    for (int row = count - 1; row >= 0; --row) {
      body(row);
      ++rows_seen;
    }
  };
  const ParallelRows threads = [](int count, const std::function<void(int)>& body) {
    std::vector<std::thread> pool;
    for (int row = 0; row < count; ++row) {
      pool.emplace_back([&body, row] { body(row); });
    }
    for (std::thread& t : pool) {
      t.join();
    }
  };
  for (const Variant& v : camera_variants()) {
    const Scene scene = resolve_scene(v.preset, v.overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan serial = make_frame_plan(scene, lattice);
    INFO(v.preset << " " << v.overrides.back());
    CHECK(same(make_frame_plan(scene, lattice, nullptr, backwards).projector, serial.projector));
    CHECK(same(make_frame_plan(scene, lattice, nullptr, threads).projector, serial.projector));
  }
  CHECK(rows_seen > 0);  // the hook ran: the refinement's rows went through it
}

}  // namespace
}  // namespace relief
