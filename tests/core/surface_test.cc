#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/surface.h"
#include "core/terrain_stages.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// A terrain that is an exact plane: bilinear interpolation of L(i, j) = alpha i + beta j
// over one octave. Its gradient is known in closed form.
NoiseLattice planar_lattice(float alpha, float beta) {
  NoiseLattice l;
  l.size = 4096;
  l.mask = 4095;
  l.values.resize(4096ull * 4096);
  for (int j = 0; j < 4096; ++j) {
    for (int i = 0; i < 4096; ++i) {
      l.values[static_cast<std::size_t>(j) * 4096 + i] = alpha * float(i) + beta * float(j);
    }
  }
  l.min_value = 0;
  l.max_value = 4095 * (alpha + beta);
  return l;
}

TEST_CASE("surfacePassRecoversTheGradientOfAPlane", "[surface]") {
  const float alpha = 1.0f / 512, beta = 1.0f / 1024;
  const NoiseLattice lattice = planar_lattice(alpha, beta);
  Scene scene = test::small_scene(48);
  scene.terrain.first_octave = scene.terrain.last_octave = 0;
  scene.terrain.interpolant = Interpolant::kLinear;
  scene.terrain.lattice_size = 4096;
  scene.terrain.horizontal_scale = 4.0;
  scene.terrain.amplitude = 100.0;
  // Above the plane (heights 100 .. 1300 over the lattice): the projector covers only ground
  // whose terrain the camera can see (core/projector.h).
  scene.camera.position = {0, 1500, 0};
  scene.camera.pitch_deg = -40;
  scene.camera.far = 2000;
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<double> b(plan.layout);
  run_terrain_stages(plan, b);
  // h = A (alpha px + beta pz), px = offset + x / scale: dh/dx = A alpha / scale.
  const double gx = 100.0 * alpha / 4.0, gz = 100.0 * beta / 4.0;
  const double norm = std::sqrt(1 + gx * gx + gz * gz);
  int checked = 0;
  for (int j = 0; j < b.layout.height; ++j) {
    for (int i = 0; i < b.layout.width; ++i) {
      const std::size_t k = b.layout.index(i, j);
      if (!b.valid[k]) {
        continue;
      }
      // The lattice seam (where the plane wraps back) is not part of the plane.
      const double px = plan.terrain.octaves.offset_x[0] + b.dx[k] / 4.0;
      const double pz = plan.terrain.octaves.offset_z[0] + b.dz[k] / 4.0;
      if (px < 50 || px > 4000 || pz < 50 || pz > 4000) {
        continue;
      }
      ++checked;
      REQUIRE(b.nx[k] == Approx(-gx / norm).margin(1e-9));
      REQUIRE(b.ny[k] == Approx(1 / norm).margin(1e-9));
      REQUIRE(b.nz[k] == Approx(-gz / norm).margin(1e-9));
      REQUIRE(b.slope[k] == Approx(std::hypot(gx, gz)).epsilon(1e-9));
    }
  }
  CHECK(checked > 500);
}

TEST_CASE("surfaceNormalsAreUnitAndPointUp", "[surface]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (bool warp : {false, true}) {
    Scene scene = test::small_scene(80);
    scene.terrain.warp.enabled = warp;
    const FramePlan plan = make_frame_plan(scene, lattice);
    GridBuffers<float> b(plan.layout);
    run_terrain_stages(plan, b);
    for (std::size_t k = 0; k < b.layout.size(); ++k) {
      const double length = std::sqrt(double(b.nx[k]) * b.nx[k] + double(b.ny[k]) * b.ny[k] +
                                      double(b.nz[k]) * b.nz[k]);
      REQUIRE(length == Approx(1.0).margin(1e-6));
      REQUIRE(b.ny[k] > 0.0f);
      // slope = |grad h| = sqrt(nx^2 + nz^2) / ny for a unit normal.
      REQUIRE(b.slope[k] ==
              Approx(std::hypot(b.nx[k], b.nz[k]) / b.ny[k]).epsilon(1e-4).margin(1e-6));
    }
  }
}

TEST_CASE("waterDepthIsZeroAboveTheWaterLevelAndTheDepthBelowIt", "[surface]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  Scene scene = test::small_scene(64);
  scene.terrain.water_level = 35.0;
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> b(plan.layout);
  run_terrain_stages(plan, b);
  // Heights are camera-relative: the water level too, formed in double and rounded once.
  const float level = static_cast<float>(35.0 - scene.camera.position[1]);
  int wet = 0, dry = 0;
  for (std::size_t k = 0; k < b.layout.size(); ++k) {
    if (!b.valid[k]) {
      REQUIRE(b.water_depth[k] == 0.0f);
    } else if (b.height[k] >= level) {
      ++dry;
      REQUIRE(b.water_depth[k] == 0.0f);
    } else {
      ++wet;
      REQUIRE(b.water_depth[k] == level - b.height[k]);
    }
  }
  CHECK(wet > 0);
  CHECK(dry > 0);

  scene.terrain.water_level.reset();  // no water: the pass writes zero everywhere
  const FramePlan dry_plan = make_frame_plan(scene, lattice);
  run_terrain_stages(dry_plan, b);
  for (float depth : b.water_depth) {
    REQUIRE(depth == 0.0f);
  }
}

TEST_CASE("normalsAreTheSameForAWholeSceneScaledDownByAPowerOfTwo", "[surface]") {
  // Scaling every length of a scene (camera, near, far, horizontal scale, base height,
  // amplitude, water) by 2^-42 shows the same picture, with spacings near 1e-13 units. The
  // products of four tangent components once underflowed there (normals off by up to 0.58 per
  // component); each tangent is now scaled by its largest component first.
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  const Scene scene = test::small_scene(64);
  Scene small = scene;
  const double s = 0x1p-42;
  for (double& c : small.camera.position) {
    c *= s;
  }
  small.camera.near *= s;
  small.camera.far *= s;
  small.terrain.horizontal_scale *= s;
  small.terrain.base_height *= s;
  small.terrain.amplitude *= s;
  *small.terrain.water_level *= s;
  const FramePlan plan = make_frame_plan(scene, lattice);
  const FramePlan small_plan = make_frame_plan(small, lattice);
  GridBuffers<float> a(plan.layout), b(small_plan.layout);
  run_terrain_stages(plan, a);
  run_terrain_stages(small_plan, b);
  double worst = 0;
  int compared = 0;
  for (std::size_t k = 0; k < a.layout.size(); ++k) {
    if (a.valid[k] && b.valid[k]) {
      ++compared;
      worst = std::max({worst, double(std::abs(a.nx[k] - b.nx[k])),
                        double(std::abs(a.ny[k] - b.ny[k])), double(std::abs(a.nz[k] - b.nz[k]))});
    }
  }
  INFO(compared << " vertices, largest normal component difference " << worst);
  CHECK(compared > 1000);
  CHECK(worst < 1e-4);
}

}  // namespace
}  // namespace relief
