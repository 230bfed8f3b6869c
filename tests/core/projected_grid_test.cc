#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_bound_pyramid.h"
#include "core/lattice.h"
#include "core/projected_domain.h"
#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "core/terrain_stages.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

struct CameraCase {
  std::string name;
  double height;
  double pitch_deg;
  double fov_y_deg = 60;
};

std::vector<CameraCase> camera_cases() {
  return {{"level, low", 30.0, 0.0},
          {"level, inside the height slab", 420.0, 0.0},
          {"looking down", 1500.0, -55.0},
          {"straight down", 800.0, -90.0},
          {"grazing at the horizon", 200.0, -1.0},
          {"looking up", 100.0, 25.0},
          {"high above the slab", 20000.0, -30.0},
          {"below every possible height", -5000.0, 10.0},
          {"wide angle", 300.0, -10.0, 150.0}};
}

Scene scene_for(const CameraCase& c) {
  Scene scene = test::small_scene(64);
  scene.camera.position = {1234.5, c.height, -987.25};
  scene.camera.yaw_deg = 37.0;
  scene.camera.pitch_deg = c.pitch_deg;
  scene.camera.fov_y_deg = c.fov_y_deg;
  scene.viewport = {1280, 1024};
  return scene;
}

// Is the camera-relative base point (x, z) inside the footprint of one of the grid's cells?
// Located through the projector image (rows are regular in image y, each row regular in x
// over its own span, screen_grid.h), then tested against the real stage-2 footprints of the
// corners of the cells around that image point.
bool covered_by_grid(const FramePlan& plan, const GridBuffers<double>& b, double x, double z) {
  const Projector& p = plan.projector;
  const glm::dvec3 foot(x, -p.height_above_plane, z);
  const double depth = glm::dot(foot, p.forward);
  if (!(depth > 0)) {
    return false;
  }
  const double ix = glm::dot(foot, p.right) / depth;
  const int j = static_cast<int>(
      std::floor((glm::dot(foot, p.up) / depth - plan.screen.y0) / plan.screen.step_y));
  if (j < 0 || j + 1 >= b.layout.height) {
    return false;
  }
  // The point's column in the two rows around it; the cell lies between them.
  const double g0 = (ix - plan.screen.row_origin(j)) / plan.screen.row_step(j);
  const double g1 = (ix - plan.screen.row_origin(j + 1)) / plan.screen.row_step(j + 1);
  const int first = static_cast<int>(std::floor(std::min(g0, g1))) - 1;
  const int last = static_cast<int>(std::floor(std::max(g0, g1))) + 1;
  for (int i = std::max(first, 0); i <= last && i + 1 < b.layout.width; ++i) {
    const std::size_t corners[4] = {b.layout.index(i, j), b.layout.index(i + 1, j),
                                    b.layout.index(i + 1, j + 1), b.layout.index(i, j + 1)};
    if (!(b.valid[corners[0]] && b.valid[corners[1]] && b.valid[corners[2]] &&
          b.valid[corners[3]])) {
      continue;
    }
    // Point in convex quad (footprints of a projective map of a convex quad are convex): the
    // signs of the cross products must agree, within a relative tolerance for points on an
    // edge.
    int positive = 0, negative = 0;
    for (int e = 0; e < 4; ++e) {
      const std::size_t a = corners[e], c = corners[(e + 1) % 4];
      const double ex = b.dx[c] - b.dx[a], ez = b.dz[c] - b.dz[a];
      const double cross = ex * (z - b.dz[a]) - ez * (x - b.dx[a]);
      const double scale = std::hypot(ex, ez) * (std::hypot(x - b.dx[a], z - b.dz[a]) + 1e-9);
      positive += cross > 1e-9 * scale;
      negative += cross < -1e-9 * scale;
    }
    if (positive == 0 || negative == 0) {
      return true;
    }
  }
  return false;
}

// Figure 5's requirement: every point of the view frustum where the terrain can be (a height
// within the regional bound at its base point, height_bound_pyramid.h) is over the grid. The
// points of the global slab that the regional bound rules out need not be: that is the
// projector's refinement (projector.h).
TEST_CASE("projectedGridCoversEveryBasePointVisibleInTheViewport", "[projected_grid]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  const LatticeRangePyramid pyramid = make_lattice_range_pyramid(lattice);
  for (const CameraCase& c : camera_cases()) {
    const Scene scene = scene_for(c);
    const FramePlan plan = make_frame_plan(scene, lattice);
    INFO("camera: " << c.name);
    REQUIRE(plan.projector.terrain_visible);
    const RegionalHeightBound regional(plan.terrain, pyramid);
    GridBuffers<double> b(plan.layout);
    project_domain<double>(make_terrain_params<double>(plan).domain, make_domain_rows<double>(plan),
                           RowRange{0, plan.layout.height}, b.domain());
    const CameraFrame& cam = plan.camera;
    int tested = 0;
    const ValueRange slab = regional.global();
    // Rays through a 41 x 41 lattice of viewport points, corners and edges included; on each,
    // points spread over the part of the ray inside the height slab, up to the far plane.
    for (int sy = 0; sy <= 40; ++sy) {
      for (int sx = 0; sx <= 40; ++sx) {
        const double ndc_x = -1.0 + sx / 20.0, ndc_y = -1.0 + sy / 20.0;
        const glm::dvec3 dir = cam.forward + ndc_x * cam.tan_half_fov_x * cam.right +
                               ndc_y * cam.tan_half_fov_y * cam.up;  // depth 1 along forward
        // The depths where the ray is inside the slab (y = depth dir.y, linear in depth).
        double d0 = cam.near, d1 = cam.far;
        if (dir.y != 0.0) {
          const double at_lo = slab.lo / dir.y, at_hi = slab.hi / dir.y;
          d0 = std::max(d0, std::min(at_lo, at_hi));
          d1 = std::min(d1, std::max(at_lo, at_hi));
        }
        for (int s = 0; s <= 60 && d0 < d1; ++s) {
          const double depth = d0 * std::pow(d1 / d0, s / 60.0);
          const glm::dvec3 p = depth * dir;
          const double r = 1e-6 * (std::abs(p.x) + std::abs(p.z)) + 1e-9;
          const ValueRange h = regional.bound(p.x - r, p.x + r, p.z - r, p.z + r);
          if (p.y < h.lo || p.y > h.hi) {
            continue;
          }
          ++tested;
          INFO("ndc " << ndc_x << ", " << ndc_y << " depth " << depth);
          REQUIRE(covered_by_grid(plan, b, p.x, p.z));
        }
      }
    }
    CHECK(tested > 100);
  }
}

TEST_CASE("projectedGridSpacingGrowsAndOctavesFallWithDistance", "[projected_grid]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (const CameraCase& c : camera_cases()) {
    if (c.pitch_deg == -90.0) {
      continue;  // looking straight down, distance does not grow along a grid column
    }
    const Scene scene = scene_for(c);
    const FramePlan plan = make_frame_plan(scene, lattice);
    GridBuffers<double> b(plan.layout);
    project_domain<double>(make_terrain_params<double>(plan).domain, make_domain_rows<double>(plan),
                           RowRange{0, plan.layout.height}, b.domain());
    INFO("camera: " << c.name);
    // Along the centre column, the valid vertices of the covered region (the margin rows may
    // reach behind the camera), in order of their distance ahead of it.
    const int i = plan.layout.width / 2;
    const int margin = scene.grid.margin;
    const glm::dvec3 ahead = glm::cross(glm::dvec3(0, 1, 0), plan.camera.right);
    std::vector<std::size_t> column;
    for (int j = margin; j < plan.layout.height - margin; ++j) {
      if (b.valid[b.layout.index(i, j)]) {
        column.push_back(b.layout.index(i, j));
      }
    }
    const auto distance_ahead = [&](std::size_t k) {
      return b.dx[k] * ahead.x + b.dz[k] * ahead.z;
    };
    std::sort(column.begin(), column.end(), [&](std::size_t a, std::size_t c2) {
      return distance_ahead(a) < distance_ahead(c2);
    });
    REQUIRE(column.size() > 10);
    for (std::size_t k = 1; k < column.size(); ++k) {
      REQUIRE(b.sigma[column[k]] >= b.sigma[column[k - 1]] * (1 - 1e-9));
      REQUIRE(b.nu[column[k]] <= b.nu[column[k - 1]] + 1e-12);
    }
    CHECK(b.sigma[column.back()] > 2 * b.sigma[column.front()]);
  }
}

TEST_CASE("projectedGridOutputsAreFiniteAndInRange", "[projected_grid]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (const CameraCase& c : camera_cases()) {
    const Scene scene = scene_for(c);
    const FramePlan plan = make_frame_plan(scene, lattice);
    GridBuffers<float> b(plan.layout);
    run_terrain_stages(plan, b);
    INFO("camera: " << c.name);
    int valid = 0;
    for (std::size_t k = 0; k < b.layout.size(); ++k) {
      for (float v : {b.dx[k], b.dz[k], b.sigma[k], b.nu[k], b.height[k], b.nx[k], b.ny[k], b.nz[k],
                      b.slope[k], b.water_depth[k]}) {
        REQUIRE(std::isfinite(v));
      }
      REQUIRE(b.nu[k] >= 1.0f);
      REQUIRE(b.nu[k] <= float(plan.lod.nu_max));
      valid += b.valid[k];
    }
    CHECK(valid > b.layout.width * b.layout.height / 4);
  }
}

TEST_CASE("projectorSeesNothingWhenTheFrustumMissesTheHeightSlab", "[projected_grid]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  Scene scene = test::small_scene(32);
  scene.camera.position = {0, 1e6, 0};
  scene.camera.pitch_deg = 60;  // looking up, far above every possible height
  const FramePlan plan = make_frame_plan(scene, lattice);
  CHECK_FALSE(plan.projector.terrain_visible);
  GridBuffers<float> b(plan.layout);
  run_terrain_stages(plan, b);
  CHECK(std::all_of(b.valid.begin(), b.valid.end(), [](std::uint8_t v) { return v == 0; }));
}

TEST_CASE("nyquistCriterionGivesOneOctaveLessPerDoublingOfTheSpacing", "[projected_grid]") {
  TerrainSettings t;
  t.lod.criterion = LodCriterion::kNyquist;
  const LodPlan lod = make_lod_plan(t);
  // nu(sigma) = c0 - c1 log2(sigma^2); at r = 2 doubling sigma removes exactly one octave.
  const auto nu = [&](double sigma) { return lod.c0 - lod.c1 * std::log2(sigma * sigma); };
  CHECK(nu(10.0) - nu(20.0) == Approx(1.0));
  // The octave whose lattice cell spans two spacings is the last whole one.
  const double sigma = t.horizontal_scale / std::pow(2.0, 6) / 2;  // cell of octave 6 = 2 sigma
  CHECK(nu(sigma) == Approx(7.0));
  t.lod.criterion = LodCriterion::kAmplitude;
  const LodPlan amp = make_lod_plan(t);
  // §4.1: nu = log(sigma) / (-H log r) (+ the octaves before): amplitude of octave nu-1 is sigma.
  const double s = t.amplitude * std::pow(2.0, -3 * t.H);
  CHECK(amp.c0 - amp.c1 * std::log2(s * s) == Approx(4.0));
}

TEST_CASE("withoutTheFractionalOctaveEveryVertexSumsWholeOctavesRoundedUp", "[projected_grid]") {
  // §4.1's geomorphing off: nu is the fractional count rounded up, never more than N, and the
  // heights are the fBm of that whole count (the fractional octave's weight is 0 or 1).
  const std::vector<std::string> size = {"grid.width=97", "grid.height=61",
                                         "terrain.lod.bias=0.37"};
  Scene scene = resolve_scene("default", size);
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan smooth_plan = make_frame_plan(scene, lattice);
  scene.terrain.lod.fractional = false;
  const FramePlan whole_plan = make_frame_plan(scene, lattice);
  GridBuffers<float> smooth(smooth_plan.layout), whole(whole_plan.layout);
  run_terrain_stages(smooth_plan, smooth);
  run_terrain_stages(whole_plan, whole);
  int fractional = 0, checked = 0;
  for (std::size_t k = 0; k < smooth.layout.size(); ++k) {
    if (!smooth.valid[k]) {
      continue;
    }
    REQUIRE(whole.valid[k]);
    CHECK(whole.nu[k] == std::ceil(smooth.nu[k]));
    CHECK(whole.nu[k] <= float(smooth_plan.lod.nu_max));
    fractional += smooth.nu[k] != std::floor(smooth.nu[k]);
    if (k % 97 == 0) {
      // The frame's own coordinate forms may round the last bits differently from
      // fbm_height's; a fractional weight would be off by far more.
      const float direct =
          fbm_height<float>(whole_plan.terrain, whole.dx[k], whole.dz[k], whole.nu[k]);
      CHECK(std::abs(whole.height[k] - direct) <= 1e-5f * float(scene.terrain.amplitude));
      ++checked;
    }
  }
  CHECK(fractional > 0);  // the default frame has fractional counts to round
  CHECK(checked > 10);
  // The scene file says so, and reads back.
  CHECK(resolve_scene("default", {"terrain.lod.fractional=false"}).terrain.lod.fractional == false);
  CHECK_THROWS(resolve_scene("default", {"terrain.lod.fractional=1"}));
}

}  // namespace
}  // namespace relief
