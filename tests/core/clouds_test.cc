// The cloud layer's functions (core/clouds.h, core/cloud_plan.h) against oracles of their own:
// the normal quantile against erfc, the fBm's spread and the coverage against sampled
// lattices, the path inside the band against a fine march along the ray, the far field's mean
// against the layer's average; every output finite over hostile inputs.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <catch2/catch.hpp>

#include "core/cloud_plan.h"
#include "core/clouds.h"
#include "core/interpolant.h"
#include "core/lattice.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kCloudLatticeSize = 256;

const NoiseLattice& cloud_lattice() {
  static const NoiseLattice lattice = make_noise_lattice(7, kCloudLatticeSize);
  return lattice;
}

// Stage 8's parameters with the layer `s`, the camera at (cx, cy, cz).
template <class Real>
ShadeParams<Real> cloud_params(const CloudSettings& s, glm::dvec3 camera = {0, 0, 0},
                               double sun_elevation_deg = 40.0) {
  ShadingPlan plan;
  const double e = sun_elevation_deg * 3.141592653589793 / 180.0;
  plan.light.sun_direction = glm::dvec3(0.6 * std::cos(e), std::sin(e), 0.8 * std::cos(e));
  plan.light.sun = glm::dvec3(1.8);
  plan.light.sky = glm::dvec3(0.1, 0.15, 0.2);
  plan.pixel_angle = 1e-3;
  plan.clouds = make_cloud_plan(s, camera, -1e4, plan.light.sun_direction, plan.light.sun,
                                plan.light.sky, 0.03, kCloudLatticeSize);
  return make_shade_params<Real>(plan);
}

// An even overcast 300 units thick from height 1000, extinction 0.002 per unit: full
// everywhere, so a path's depth is 0.002 x its length exactly.
CloudSettings even_overcast() {
  CloudSettings s;
  s.altitude = 1000.0;
  s.coverage = 1.0;
  s.density = 0.002;
  return s;
}

// The layer's own light where the cloud is full (the sky's, the sun's through half the layer).
template <class Real>
Real full_cloud_light(const ShadeParams<Real>& p) {
  return p.cloud_sky_light.x + p.cloud_sun_light.x * std::exp2(-p.cloud_sun_depth_log2);
}

double standard_normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

TEST_CASE("theNormalQuantileInvertsTheNormalDistribution", "[clouds]") {
  for (double p = 1e-6; p < 1.0; p = p < 0.01 ? p * 3.0 : p + 0.0137) {
    INFO("p = " << p);
    CHECK(standard_normal_cdf(normal_quantile(p)) == Approx(p).epsilon(1e-7));
  }
  CHECK(normal_quantile(0.5) == Approx(0.0).margin(1e-12));
  CHECK(normal_quantile(0.975) == Approx(1.959963984540054).epsilon(1e-8));
}

// Points of the layer spread over many cells, seeded.
std::vector<std::pair<double, double>> layer_points(int count) {
  test::TestRandom random(11);
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < count; ++i) {
    const double x = random.uniform(-2e5, 2e5);
    out.emplace_back(x, random.uniform(-2e5, 2e5));
  }
  return out;
}

TEST_CASE("theFbmSpreadIsTheOneTheCoverageAssumes", "[clouds]") {
  // The sum of the octaves as the layer sums them, sampled: its standard deviation against
  // cloud_fbm_sigma's closed form (26/35 per axis of a cubic-faded lattice of N(0, 1) values).
  for (int octaves : {1, 3, 5, 8}) {
    CloudSettings s;
    s.octaves = octaves;
    s.warp = 0.0;
    const ShadeParams<double> p = cloud_params<double>(s);
    double sum = 0, sum_sq = 0;
    const auto points = layer_points(40000);
    for (const auto& [x, z] : points) {
      double n = 0;
      for (int i = 0; i < octaves; ++i) {
        n += p.cloud_amplitude[i] *
             sample_lattice<Interpolant::kCubic>(cloud_lattice(),
                                                 p.cloud_offset_x[i] + x * p.cloud_inv_scale[i],
                                                 p.cloud_offset_z[i] + z * p.cloud_inv_scale[i]);
      }
      sum += n;
      sum_sq += n * n;
    }
    const double mean = sum / points.size();
    const double sigma = std::sqrt(sum_sq / points.size() - mean * mean);
    INFO(octaves << " octaves: sampled " << sigma << ", closed form " << cloud_fbm_sigma(octaves));
    CHECK(sigma == Approx(cloud_fbm_sigma(octaves)).epsilon(0.06));
  }
}

TEST_CASE("theCoverageIsTheShareOfTheLayerHoldingCloud", "[clouds]") {
  const auto points = layer_points(20000);
  for (double coverage : {0.0, 0.15, 0.45, 0.8, 1.0}) {
    CloudSettings s;
    s.coverage = coverage;
    const ShadeParams<double> p = cloud_params<double>(s);
    ShadeWork work;
    int cloudy = 0;
    double density_sum = 0;
    for (const auto& [x, z] : points) {
      const double d = cloud_density(p, cloud_lattice(), x, z, 0.0, work);
      REQUIRE(d >= 0.0);
      REQUIRE(d <= 1.0);
      cloudy += d > 0.0;
      density_sum += d;
    }
    const double share = double(cloudy) / points.size();
    INFO("coverage " << coverage << ": share " << share << ", mean " << density_sum / points.size()
                     << " against the plan's " << p.cloud_mean_density);
    CHECK(share == Approx(coverage).margin(0.06));
    // The far field's density (every octave under the footprint) is the layer's average.
    CHECK(p.cloud_mean_density == Approx(density_sum / points.size()).margin(0.03));
    CHECK(cloud_density(p, cloud_lattice(), 123.0, 456.0, 1e9, work) == p.cloud_mean_density);
  }
}

TEST_CASE("aCoverageTooSmallToLeaveOneIsNoCloud", "[clouds]") {
  // 1 - 1e-17 is 1 in double: no quantile to take (log's argument would be 0); as coverage 0.
  for (const double coverage : {0.0, 1e-17, 1e-300}) {
    CloudSettings s;
    s.coverage = coverage;
    CHECK(cloud_params<double>(s).cloud_threshold == kCloudThresholdBeyond);
  }
  CloudSettings full;
  full.coverage = 1.0;
  CHECK(cloud_params<double>(full).cloud_threshold == -kCloudThresholdBeyond);
  CloudSettings almost;
  almost.coverage = 1e-12;
  CHECK(std::isfinite(cloud_params<double>(almost).cloud_threshold));
}

TEST_CASE("aPathLiesInTheLayerWhereAFineMarchFindsIt", "[clouds]") {
  // The band's heights relative to the camera: [-50, 250] (the camera inside), [100, 400]
  // (below it), [-900, -600] (above it); rays up, down, level and grazing; ends before, inside
  // and beyond the band.
  test::TestRandom random(3);
  const auto unit = [&] { return random.uniform(-1.0, 1.0); };
  for (const double bottom : {-50.0, 100.0, -900.0}) {
    CloudSettings s;
    s.altitude = bottom;
    s.thickness = 300.0;
    const ShadeParams<double> p = cloud_params<double>(s);
    for (int trial = 0; trial < 400; ++trial) {
      const double y0 = trial % 4 == 0 ? 0.0 : 600.0 * unit();
      double dy = trial % 7 == 0 ? 0.0 : unit();
      if (trial % 11 == 0) {
        dy = 1e-5 * unit();
      }
      const double end = trial % 5 == 0 ? 1e11 : 3000.0 * (unit() + 1.0);
      const CloudPath<double> path = cloud_path(p, y0, dy, end);
      REQUIRE(std::isfinite(path.start));
      REQUIRE(std::isfinite(path.length));
      REQUIRE(path.length >= 0.0);
      // The march: heights y0 + t dy for t in [0, min(end, 1e5)] (a level ray inside the band
      // is in it all the way), the slope floored as the layer floors it.
      const double slope = dy >= 0 ? std::max(dy, kCloudMinSlope) : std::min(dy, -kCloudMinSlope);
      const double reach = std::min(end, 1e5);
      constexpr int kSteps = 200000;
      double inside = 0;
      for (int k = 0; k < kSteps; ++k) {
        const double t = (k + 0.5) * reach / kSteps;
        const double y = y0 + t * slope;
        inside += (y >= p.cloud_bottom && y <= p.cloud_top) ? reach / kSteps : 0.0;
      }
      INFO("bottom " << bottom << ", y0 " << y0 << ", dy " << dy << ", end " << end);
      CHECK(std::min(path.length, std::max(0.0, reach - path.start)) ==
            Approx(inside).margin(3.0 * reach / kSteps));
    }
  }
}

TEST_CASE("theSunsShareThroughTheLayerFallsWithItsDensityAndIsOneAboveIt", "[clouds]") {
  const CloudSettings s = even_overcast();
  const ShadeParams<double> p = cloud_params<double>(s, {0, 0, 0}, 30.0);
  ShadeWork work;
  const double share = cloud_sun_share(p, cloud_lattice(), Vec3<double>{0, 0, 0}, 0.0, work);
  // Under the layer, 300 units thick, the sun at 30 degrees: a path of 600 units.
  CHECK(share == Approx(std::exp(-0.002 * 600.0)).epsilon(1e-6));
  CHECK(cloud_sun_share(p, cloud_lattice(), Vec3<double>{0, 2000, 0}, 0.0, work) == 1.0);
  CHECK(work.cloud_sun_paths == 1);
  // Inside the layer, half of it lies above.
  CHECK(cloud_sun_share(p, cloud_lattice(), Vec3<double>{0, 1150, 0}, 0.0, work) ==
        Approx(std::exp(-0.002 * 300.0)).epsilon(1e-6));
  // The sun below the horizon: its ray goes down and never meets the layer above.
  const ShadeParams<double> night = cloud_params<double>(s, {0, 0, 0}, -5.0);
  CHECK(cloud_sun_share(night, cloud_lattice(), Vec3<double>{0, 0, 0}, 0.0, work) == 1.0);
}

TEST_CASE("theLayerOverTheSkyIsOpaqueOnlyWhereItsDepthIs", "[clouds]") {
  const CloudSettings s = even_overcast();
  ShadeParams<double> p = cloud_params<double>(s);
  p.fog_enabled = 0;
  ShadeWork work;
  const Vec3<double> sky{0.2, 0.3, 0.6};
  const Vec3<double> up{0, 1, 0};
  const Vec3<double> seen = clouds_over(p, cloud_lattice(), sky, up, 1e11, work);
  const double t = std::exp(-0.002 * 300.0);
  const double light = full_cloud_light(p);
  CHECK(seen.x == Approx(sky.x * t + light * (1 - t)).epsilon(1e-6));
  // Looking down from under the layer, or at ground before it: untouched.
  const Vec3<double> down{0, -1, 0};
  CHECK(clouds_over(p, cloud_lattice(), sky, down, 1e11, work).x == sky.x);
  CHECK(clouds_over(p, cloud_lattice(), sky, up, 999.0, work).x == sky.x);
  CHECK(work.cloud_view_paths == 1);
}

TEST_CASE("aPathFromAPointSeesTheLayerAboveIt", "[clouds]") {
  // The water's reflected ray: from a point under an even overcast straight up, the layer's
  // whole thickness, wherever the point lies; from the camera, clouds_over to the bit.
  const CloudSettings s = even_overcast();
  ShadeParams<float> p = cloud_params<float>(s);
  p.fog_enabled = 0;
  ShadeWork work;
  const Vec3<float> black{0, 0, 0}, up{0, 1, 0};
  const float light = full_cloud_light(p);
  for (const Vec3<float> origin : {Vec3<float>{0, -50, 0}, Vec3<float>{5000, 300, -7000}}) {
    const Vec3<float> c =
        clouds_over_from(p, cloud_lattice(), black, origin, 800.0f, up, 1e11f, work);
    CHECK(c.x == Approx(light * (1.0 - std::exp(-0.002 * 300.0))).epsilon(1e-5));
  }
  const Vec3<float> d = normalize_or(Vec3<float>{0.3f, 0.2f, -0.9f}, up);
  const Vec3<float> sky{0.2f, 0.3f, 0.6f};
  const Vec3<float> a = clouds_over(p, cloud_lattice(), sky, d, 1e11f, work);
  const Vec3<float> b =
      clouds_over_from(p, cloud_lattice(), sky, Vec3<float>{0, 0, 0}, 0.0f, d, 1e11f, work);
  CHECK(std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x));
  CHECK(std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z));
}

TEST_CASE("theLayerStaysFiniteOverHostileInputs", "[clouds]") {
  const double huge = 1e11;
  for (const double density : {0.0, 1e-9, 100.0}) {
    for (const double thickness : {limits::kMinCloudThickness, 300.0, limits::kMaxShadingLength}) {
      for (const double altitude : {-limits::kMaxBaseHeight, 0.0, limits::kMaxBaseHeight}) {
        CloudSettings s;
        s.density = density;
        s.thickness = thickness;
        s.altitude = altitude;
        s.octaves = limits::kMaxCloudOctaves;
        s.scale = limits::kMinCloudScale;
        s.warp = limits::kMaxCloudWarp;
        for (const double sun : {-90.0, 0.0, 90.0}) {
          const ShadeParams<float> p =
              cloud_params<float>(s, {limits::kMaxCameraCoordinate, 0.0, -1e9}, sun);
          ShadeWork work;
          for (const float dy : {-1.0f, -1e-7f, 0.0f, 1e-7f, 1.0f}) {
            const float dx = std::sqrt(1.0f - dy * dy);
            const Vec3<float> d{dx, dy, 0.0f};
            for (const float end : {0.0f, 1.0f, float(huge)}) {
              const Vec3<float> c =
                  clouds_over(p, cloud_lattice(), Vec3<float>{1, 1, 1}, d, end, work);
              REQUIRE(std::isfinite(c.x));
              REQUIRE(std::isfinite(c.y));
              REQUIRE(std::isfinite(c.z));
              REQUIRE(c.x >= 0.0f);
            }
            const float share = cloud_sun_share(p, cloud_lattice(),
                                                Vec3<float>{float(huge), float(-huge) * dy, 0.0f},
                                                float(huge), work);
            REQUIRE(std::isfinite(share));
            REQUIRE(share >= 0.0f);
            REQUIRE(share <= 1.0f);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
