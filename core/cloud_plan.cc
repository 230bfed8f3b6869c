#include "core/cloud_plan.h"

#include <algorithm>
#include <cmath>

#include "core/atmosphere.h"
#include "core/det_math.h"

namespace relief {

namespace {

// x mod period in [0, period); x finite.
double wrapped(double x, double period) {
  const double r = std::fmod(x, period);
  return r < 0.0 ? r + period : r;
}

// E[clamp((X - t) k, 0, 1)] for X ~ N(0, sigma^2): the midpoint rule over +-12 sigma in 4096
// steps (the density is piecewise linear in X, the weight smooth: error far below float's).
double expected_density(double sigma, double threshold, double sharpness) {
  if (threshold >= kCloudThresholdBeyond) {
    return 0.0;
  }
  if (threshold <= -kCloudThresholdBeyond) {
    return 1.0;
  }
  constexpr int kSteps = 4096;
  const double span = 24.0 * sigma, step = span / kSteps;
  double sum = 0.0, weight = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = -12.0 * sigma + (i + 0.5) * step;
    const double u = x / sigma;
    const double w = exp2_det(-0.5 * u * u / kLn2);
    sum += w * std::clamp((x - threshold) * sharpness, 0.0, 1.0);
    weight += w;
  }
  return sum / weight;  // weight > 0: the middle steps' weights are near 1
}

}  // namespace

double cloud_fbm_sigma(int octaves) {
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < octaves; ++i) {
    const double a = std::ldexp(1.0, -i);
    sum += a;
    sum_sq += a * a;
  }
  // octaves >= 1: sum >= 1.
  return (26.0 / 35.0) * std::sqrt(sum_sq) / sum;
}

double normal_quantile(double p) {
  // Acklam's coefficients.
  constexpr double a[6] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                           1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  constexpr double b[5] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                           6.680131188771972e+01, -1.328068155288572e+01};
  constexpr double c[6] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                           -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  constexpr double d[4] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                           3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  const auto tail = [&](double q) {  // q = sqrt(-2 ln p') for the tail's p' in (0, kLow)
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  };
  if (p < kLow) {
    return tail(std::sqrt(-2.0 * log_det(p)));  // p > 0: log's domain
  }
  if (p > 1.0 - kLow) {
    return -tail(std::sqrt(-2.0 * log_det(1.0 - p)));  // 1 - p > 0
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

CloudPlan make_cloud_plan(const CloudSettings& s, const glm::dvec3& camera, double ground_height,
                          const glm::dvec3& sun_direction, const glm::dvec3& sun,
                          const glm::dvec3& sky, double ambient, int lattice_size) {
  CloudPlan plan;
  plan.enabled = true;
  plan.octaves = s.octaves;
  plan.bottom = s.altitude - camera.y;
  plan.top = (s.altitude + s.thickness) - camera.y;
  plan.ground = ground_height - camera.y;
  plan.extinction_log2 = s.density / kLn2;
  const double sigma = cloud_fbm_sigma(s.octaves);
  // A coverage under 1.1e-16 leaves 1 - coverage = 1, whose upper quantile is beyond any
  // value (and log's argument 1 - p would be 0): no cloud, as at 0.
  if (s.coverage <= 0.0 || 1.0 - s.coverage == 1.0) {
    plan.threshold = kCloudThresholdBeyond;
  } else if (s.coverage >= 1.0) {
    plan.threshold = -kCloudThresholdBeyond;
  } else {
    plan.threshold = sigma * normal_quantile(1.0 - s.coverage);
  }
  plan.sharpness = 1.0 / sigma;  // sigma > 0
  plan.mean_density = expected_density(sigma, plan.threshold, plan.sharpness);

  // Octave i: 2^i cells per `scale`, 2^-i of the amplitude; each octave's origin shifted by
  // its own fraction of the period (the golden ratio's multiples), so that the octaves'
  // lattice points do not coincide.
  const double period = lattice_size;
  double amplitude_sum = 0.0;
  for (int i = 0; i < s.octaves; ++i) {
    amplitude_sum += std::ldexp(1.0, -i);
  }
  for (int i = 0; i < s.octaves; ++i) {
    const double inv = std::ldexp(1.0, i) / s.scale;  // scale >= kMinCloudScale > 0
    const double shift = std::fmod(0.6180339887498949 * (i + 1), 1.0);
    plan.inv_scale[i] = inv;
    plan.offset_x[i] = wrapped(camera.x * inv + shift * period, period);
    plan.offset_z[i] = wrapped(camera.z * inv + (1.0 - shift) * period, period);
    plan.amplitude[i] = std::ldexp(1.0, -i) / amplitude_sum;
    plan.warp_gain[i] = s.warp * std::ldexp(1.0, i);
  }
  plan.warped = s.warp > 0.0;
  const double inv0 = plan.inv_scale[0];
  plan.warp_offset[0] = wrapped(camera.x * inv0 + 0.31 * period, period);
  plan.warp_offset[1] = wrapped(camera.z * inv0 + 0.73 * period, period);
  plan.warp_offset[2] = wrapped(camera.x * inv0 + 0.83 * period, period);
  plan.warp_offset[3] = wrapped(camera.z * inv0 + 0.11 * period, period);

  const glm::dvec3 albedo(s.color[0], s.color[1], s.color[2]);
  const double sine = sun_direction.y;
  plan.sun_light = albedo * sun * std::max(sine, 0.0);
  plan.sky_light = albedo * (sky + glm::dvec3(ambient));
  // The sun's path to the layer's middle, half its thickness over the sine, with the extinction
  // halved: the light scattered forward stays in the beam (Wrenninge's multiple-scattering
  // octaves keep half the extinction in their first).
  plan.sun_depth_log2 =
      plan.extinction_log2 * (0.25 * s.thickness) / std::max(sine, kCloudMinSunSine);
  return plan;
}

}  // namespace relief
