#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/terrain_stages.h"
#include "test_support.h"
#include "tools/frame_runner.h"

namespace relief {
namespace {

struct FloatError {
  double height = 0;  // max |h_float - h_double| over vertices valid in both
  double normal = 0;  // max component difference
  double nu = 0;
  int compared = 0;
};

FloatError float_versus_double(const Scene& scene, const NoiseLattice& lattice) {
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> f(plan.layout);
  GridBuffers<double> d(plan.layout);
  run_terrain_stages(plan, f);
  run_terrain_stages(plan, d);
  FloatError e;
  for (std::size_t k = 0; k < f.layout.size(); ++k) {
    if (!f.valid[k] || !d.valid[k]) {
      continue;
    }
    ++e.compared;
    e.height = std::max(e.height, std::abs(f.height[k] - d.height[k]));
    e.nu = std::max(e.nu, std::abs(f.nu[k] - d.nu[k]));
    e.normal = std::max({e.normal, std::abs(f.nx[k] - d.nx[k]), std::abs(f.ny[k] - d.ny[k]),
                         std::abs(f.nz[k] - d.nz[k])});
  }
  return e;
}

// Design.md: "A camera a billion units from the origin must render as accurately as one at
// the origin." The float pipeline is compared with the double pipeline at the same camera;
// far from the origin the error may not exceed the error at the origin by more than the
// spread between different places at the origin's distance (a factor 2 covers it: the
// terrain differs from place to place, its float error statistics do not).
TEST_CASE("floatBuffersAreAsAccurateFarFromTheOriginAsAtIt", "[precision]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (double r : {2.0, 2.17}) {  // periodic and non-periodic octave tables
    for (bool warp : {false, true}) {
      Scene scene = test::small_scene(96);
      scene.terrain.r = r;
      scene.terrain.warp.enabled = warp;
      scene.camera.position = {0.0, 420.0, 0.0};
      const FloatError origin = float_versus_double(scene, lattice);
      INFO("r = " << r << ", warp " << warp << ": origin height error " << origin.height);
      REQUIRE(origin.compared > 1000);
      for (double distance : {1e3, 1e5, 1e7, 1e9}) {
        scene.camera.position = {distance * 0.6, 420.0, -distance * 0.8};
        const FloatError far = float_versus_double(scene, lattice);
        INFO("distance " << distance << ": height error " << far.height << ", normal error "
                         << far.normal);
        CHECK(far.compared == origin.compared);
        CHECK(far.height <= 2.0 * origin.height + 1e-4);
        CHECK(far.normal <= 2.0 * origin.normal + 1e-5);
        CHECK(far.nu == origin.nu);  // stage 2 is camera-relative: identical footprints
      }
    }
  }
}

template <class Real>
bool same_bits(const AlignedVector<Real>& a, const AlignedVector<Real>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

bool same_buffers(const GridBuffers<float>& a, const GridBuffers<float>& b) {
  return same_bits(a.dx, b.dx) && same_bits(a.dz, b.dz) && same_bits(a.sigma, b.sigma) &&
         same_bits(a.nu, b.nu) && a.valid == b.valid && same_bits(a.height, b.height) &&
         same_bits(a.nx, b.nx) && same_bits(a.ny, b.ny) && same_bits(a.nz, b.nz) &&
         same_bits(a.slope, b.slope) && same_bits(a.water_depth, b.water_depth);
}

TEST_CASE("movingTheCameraByWholePeriodsReproducesEveryBufferBitForBit", "[precision]") {
  // Integer lacunarity: every octave repeats every P * horizontal_scale world units. The warp
  // acts on displacements, not absolute positions, so warped terrain is periodic too.
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (bool warp : {false, true}) {
    Scene scene = test::small_scene(64);
    scene.terrain.warp.enabled = warp;
    scene.camera.position = {1234.5, 420.0, -987.25};
    const FramePlan base_plan = make_frame_plan(scene, lattice);
    REQUIRE(base_plan.terrain.octaves.periodic);
    const double period = base_plan.terrain.octaves.world_period;
    GridBuffers<float> base(base_plan.layout);
    run_terrain_stages(base_plan, base);
    for (double m : {1.0, -3.0, 1000.0, 1e6}) {
      Scene moved = scene;
      moved.camera.position[0] += m * period;
      moved.camera.position[2] -= 2 * m * period;
      const FramePlan plan = make_frame_plan(moved, lattice);
      GridBuffers<float> b(plan.layout);
      run_terrain_stages(plan, b);
      INFO("warp " << warp << ", moved by " << m << " periods");
      CHECK(same_buffers(base, b));
    }
  }
}

TEST_CASE("stageBuffersAreIdenticalForEveryThreadCountAndEqualTheSerialReference", "[precision]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  Scene scene = test::small_scene(200);
  scene.terrain.warp.enabled = true;
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> serial(plan.layout);
  run_terrain_stages(plan, serial);
  for (int threads : {1, 2, 3, 8}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    GridBuffers<float> parallel(plan.layout);
    run_terrain_stages_parallel(plan, parallel);
    INFO(threads << " threads");
    CHECK(same_buffers(serial, parallel));
  }
}

}  // namespace
}  // namespace relief
