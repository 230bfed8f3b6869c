#include "core/atmosphere_plan.h"

#include <algorithm>
#include <cmath>

#include "core/atmosphere.h"
#include "core/vec3.h"

namespace relief {

AtmospherePlan make_atmosphere_plan(const AtmosphereSettings& s, double camera_y, double elevation,
                                    double disc_radius, const glm::dvec3& sun) {
  AtmospherePlan a;
  a.enabled = true;
  a.scale_height = s.scale_height;  // >= kMinScaleHeight > 0 (validated)
  a.inv_scale_height = 1.0 / s.scale_height;
  const double log_density = std::min(-camera_y / s.scale_height, kMaxLogDensity);
  a.density = std::exp(log_density);
  a.log2_density = log_density / M_LN2;
  a.grazing_term = 8.0 * s.scale_height / (M_PI * kAtmosphereGroundRadius);
  const double sin_elevation = std::max(std::sin(elevation), 0.0);
  const double sun_slope =
      0.5 * (sin_elevation + std::sqrt(sin_elevation * sin_elevation + a.grazing_term));
  a.sun_slope_length = s.scale_height / sun_slope;
  a.sun_depth = std::min(a.density * a.sun_slope_length, kMaxOpticalDepth);

  const glm::dvec3 rayleigh(s.rayleigh[0], s.rayleigh[1], s.rayleigh[2]);
  const glm::dvec3 absorption(s.absorption[0], s.absorption[1], s.absorption[2]);
  const glm::dvec3 extinction = rayleigh + glm::dvec3(s.mie / 0.9) + absorption;
  a.extinction_log2 = extinction / M_LN2;
  a.camera_sun_depth_log2 = a.extinction_log2 * a.sun_depth;

  // The disc's share above the horizon, a smooth step over its diameter: a set sun neither
  // lights the air nor the ground (the flat ground has no twilight).
  // Domain: disc_radius >= sky.sun_disc_deg's minimum 0.11 degrees > 0 (validated).
  const double share = smooth01((elevation + disc_radius) / (2.0 * disc_radius));
  const glm::dvec3 sky_sun = sun * (s.intensity * share);
  const double g = s.mie_g;
  a.rayleigh_sun = sky_sun * rayleigh * (3.0 / (16.0 * M_PI));
  a.mie_sun = sky_sun * (s.mie * 3.0 * (1.0 - g * g) / (8.0 * M_PI * (2.0 + g * g)));
  a.mie_a = 1.0 + g * g;
  a.mie_b = 2.0 * g;
  a.ground_sun =
      sun * share *
      glm::dvec3(std::exp(-extinction.x * a.sun_depth), std::exp(-extinction.y * a.sun_depth),
                 std::exp(-extinction.z * a.sun_depth));
  return a;
}

}  // namespace relief
