// §4.1's spherical domain, the geometry (docs/planet.md): the horizon where the closed form
// puts it, the artificial horizon, equal angular spacing from orbit against the plain
// projected grid on the sphere, the plane as the limit of a large radius, and the
// deterministic trigonometry the bend uses.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/lattice.h"
#include "core/planet_domain.h"
#include "core/stage_params.h"
#include "pipeline/frame.h"
#include "tests/support/planet_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr double kRadius = 2e6;  // the preset's

template <class Real>
TerrainRun<Real> run_planet(const Scene& scene) {
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  return run_terrain_stages<Real>(scene, lattice);
}

// Ulps of `got` from `exact` in Real's precision.
template <class Real>
double ulps(Real got, long double exact) {
  const long double ulp = std::max<long double>(
      std::numeric_limits<Real>::denorm_min(),
      std::nextafter(Real(std::fabs(double(exact))), std::numeric_limits<Real>::infinity()) -
          Real(std::fabs(double(exact))));
  return double(std::fabs((long double)(got)-exact) / ulp);
}

template <class Real>
void check_trigonometry(double sin_cos_ulps, double atan_ulps) {
  test::TestRandom random(11);
  double worst_sc = 0, worst_atan = 0;
  for (int k = 0; k < 200000; ++k) {
    const Real x = Real(random.uniform(-8.0, 8.0) * (k % 4 == 0 ? 1e-3 : 1.0));
    Real s, c;
    sin_cos_det(x, s, c);
    worst_sc =
        std::max({worst_sc, ulps(s, std::sin((long double)x)), ulps(c, std::cos((long double)x))});
    const Real y = Real(random.uniform(0.0, 10.0)), xx = Real(random.uniform(-10.0, 10.0));
    worst_atan = std::max(worst_atan, ulps(atan2_det(y, xx), std::atan2((long double)y, xx)));
  }
  INFO("sin/cos " << worst_sc << " ulp, atan2 " << worst_atan << " ulp");
  CHECK(worst_sc <= sin_cos_ulps);
  CHECK(worst_atan <= atan_ulps);
  CHECK(atan2_det(Real(0), Real(0)) == Real(0));
  CHECK(atan2_det(Real(0), Real(-1)) == Real(3.14159265358979323846));
}

TEST_CASE("deterministicSineCosineAndArctangentAreWithinAFewUlps", "[planet]") {
  // Near a multiple of pi/2 sin or cos is small and its ulp tiny: the reduction's absolute
  // error (an ulp of the argument) shows as more ulps there, hence the bound.
  check_trigonometry<float>(4.0, 3.5);
  check_trigonometry<double>(4.0, 3.5);
}

// Camera 5e4 above the datum looking at the limb, plain projected grid on the sphere.
Scene horizon_scene(std::vector<std::string> extra = {}) {
  extra.insert(extra.begin(), {"terrain.planet.equal_angle=null", "camera.pitch_deg=-20",
                               "camera.fov_y_deg=50", "terrain.amplitude=1"});
  return test::planet_scene(5e4, extra, 96);
}

TEST_CASE("theLimbLiesWhereTheGeometrySaysAndTheGridEndsThere", "[planet]") {
  const double a = 5e4;
  const TerrainRun<double> run = run_planet<double>(horizon_scene());
  const PlanetPlan& planet = run.plan.planet;
  REQUIRE(planet.visible);
  REQUIRE(planet.blend == 0.0);
  // The grazing ray's near hit: central angle acos(R / (R + a)), straight distance
  // sqrt(a (2R + a)).
  const double limb = std::acos(kRadius / (kRadius + a));
  CHECK(std::abs(planet.theta_limb - limb) <= 1e-12);
  const double theta = planet_theta_true(planet, planet.alpha_h * (1.0 - 1e-12));
  CHECK(std::abs(theta - limb) <= 1e-5 * limb);
  const double chord_x = kRadius * std::sin(theta);
  const double chord_y = kRadius * std::cos(theta) - (kRadius + a);
  CHECK(std::abs(std::hypot(chord_x, chord_y) - std::sqrt(a * (2 * kRadius + a))) <=
        1e-4 * std::sqrt(a * (2 * kRadius + a)));
  // The grid's farthest valid vertex lies at the limb, within its own grid spacing.
  const GridBuffers<double>& g = run.grid;
  double farthest = 0, spacing = 0;
  for (std::size_t k = 0; k < g.layout.size(); ++k) {
    const double rho = std::hypot(g.dx[k], g.dz[k]);
    if (g.valid[k] && rho > farthest) {
      farthest = rho;
      spacing = 2.0 * g.sigma[k];
    }
  }
  INFO("farthest arc " << farthest << ", limb " << kRadius * limb << ", spacing " << spacing);
  CHECK(farthest <= kRadius * limb * (1 + 1e-9));
  CHECK(kRadius * limb - farthest <= spacing);
}

TEST_CASE("noLandscapeIsSynthesisedBeyondTheArtificialHorizon", "[planet]") {
  const double cut = 0.5 * kRadius * std::acos(kRadius / (kRadius + 5e4));
  for (const double blend_altitude : {1e9, 1e3}) {  // plain grid, then equal angles
    const std::string band = blend_altitude > 1e8 ? "null" : "{\"begin\": 1, \"end\": 2}";
    const TerrainRun<float> run = run_planet<float>(horizon_scene(
        {"terrain.planet.horizon=" + std::to_string(cut), "terrain.planet.equal_angle=" + band}));
    const GridBuffers<float>& g = run.grid;
    double farthest = 0, spacing = 0;
    for (std::size_t k = 0; k < g.layout.size(); ++k) {
      const double rho = std::hypot(double(g.dx[k]), double(g.dz[k]));
      if (g.valid[k] && rho > farthest) {
        farthest = rho;
        spacing = 2.0 * g.sigma[k];
      }
    }
    INFO("band " << band << ": farthest " << farthest << ", cut " << cut);
    CHECK(farthest <= cut * (1 + 1e-6));
    CHECK(cut - farthest <= spacing);
  }
}

// max / min of the steps in theta between consecutive valid rows of the centre column.
double step_ratio(const GridBuffers<float>& g) {
  const int i = g.layout.width / 2;
  std::vector<double> theta;
  for (int j = 0; j < g.layout.height; ++j) {
    const std::size_t k = g.layout.index(i, j);
    if (g.valid[k]) {
      theta.push_back(std::hypot(double(g.dx[k]), double(g.dz[k])) / kRadius);
    }
  }
  REQUIRE(theta.size() > 10);
  double lo = HUGE_VAL, hi = 0;
  for (std::size_t r = 1; r < theta.size(); ++r) {
    const double step = std::abs(theta[r] - theta[r - 1]);
    lo = std::min(lo, step);
    hi = std::max(hi, step);
  }
  return hi / lo;
}

TEST_CASE("equalAngleSamplingStepsTheCentralAngleEvenlyFromOrbit", "[planet]") {
  // The preset from orbit (a = R, above the band: b = 1) against the plain grid on the sphere
  // from the same camera.
  const double equal = step_ratio(run_planet<float>(test::planet_scene(kRadius)).grid);
  const double plain = step_ratio(
      run_planet<float>(test::planet_scene(kRadius, {"terrain.planet.equal_angle=null"})).grid);
  INFO("max / min step: equal angles " << equal << ", plain projected grid " << plain);
  // Rows are uniform in the projector image, not in angle: the steps of a linear function of
  // the nadir angle vary as 1 / cos^2 of the angle off the projector's axis.
  CHECK(equal <= 4.0);
  CHECK(plain >= 4.0 * equal);
}

// The largest relative difference between each ray's arc offset on a planet of radius R and
// its footprint on the plane, over rays landing within 3 km (camera 700 units up, plain
// projected grid on the sphere).
double worst_difference_from_the_plane(double radius) {
  const Scene scene =
      resolve_scene("default", {"terrain.planet={\"radius\": " + std::to_string(radius) + "}",
                                "camera.position=[0, 800, 0]"});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  REQUIRE(plan.planet.visible);
  const TerrainParams<double> params = make_terrain_params<double>(plan);
  Projector flat = plan.projector;
  flat.height_above_plane = plan.planet.altitude;
  flat.max_footprint_distance = 1e12;
  const ProjectorRays<double> rays(flat);
  const DomainRows<double>& rows = params.domain_rows;
  int compared = 0;
  double worst = 0;
  for (int j = 0; j < plan.layout.height; j += 3) {
    for (int i = 0; i < plan.layout.width; i += 7) {
      const auto r = static_cast<std::size_t>(j + 1);
      const double x = rows.x0[r] + i * rows.step_x[r], y = plan.screen.image_y(j);
      double px = 0, pz = 0, qx = 0, qz = 0;
      const bool planar = rays.footprint(x, y, rows.descent[r], px, pz);
      const bool bent =
          planet_footprint(params.domain.rays, params.planet, x, y, rows.descent[r], qx, qz);
      const double rho = std::hypot(px, pz);
      if (planar && bent && rho < 3000) {
        ++compared;
        worst = std::max(worst, std::hypot(px - qx, pz - qz) / rho);
      }
    }
  }
  CHECK(compared > 100);
  return worst;
}

TEST_CASE("aLargePlanetsRaysLandWhereThePlanesDo", "[planet]") {
  // The sphere falls rho^2 / 2R below the plane, so a ray descending at a / rho lands
  // rho^3 / (2 R a) further: 6e-5 of rho at 3 km for R = 1e8, and ten times less each time R
  // grows tenfold.
  const double coarse = worst_difference_from_the_plane(1e7);
  const double fine = worst_difference_from_the_plane(1e8);
  INFO("worst relative difference: R = 1e7 " << coarse << ", R = 1e8 " << fine);
  CHECK(fine <= 1e-4);
  CHECK(coarse >= 5.0 * fine);
}

}  // namespace
}  // namespace relief
