// What the atmosphere (core/atmosphere.h) derives once per frame, in double, from
// sky.atmosphere, the camera's height and the sun.
#pragma once

#include <glm/vec3.hpp>

#include "core/scene/scene.h"

namespace relief {

// The ground's radius for the grazing columns (atmosphere.h): the Earth's, in world units.
inline constexpr double kAtmosphereGroundRadius = 6.371e6;
// The density at the camera is at most e^40 times height 0's (the camera 40 scale heights
// below it): columns stay finite in float, and every coefficient from 1e-18 is opaque there.
inline constexpr double kMaxLogDensity = 40.0;

struct AtmospherePlan {
  bool enabled = false;
  double density = 0;       // rho0 = exp(-camera y / H), at most e^40
  double log2_density = 0;  // log2 rho0, at most 40 / ln 2
  double scale_height = 1, inv_scale_height = 1;
  // H / mu_s, mu_s = (sin e + sqrt(sin^2 e + 4 c^2)) / 2 for the sun's elevation e, or e = 0
  // for a sun below the horizon (atmosphere.h): the sun's column above a point per unit of its
  // density.
  double sun_slope_length = 1;
  double sun_depth = 0;          // the sun's column above the camera: rho0 H / mu_s, capped at 1e20
  double grazing_term = 1;       // 4 c^2 = 8 H / (pi R): a slope is (mu + sqrt(mu^2 + 4 c^2)) / 2
  glm::dvec3 extinction_log2{};  // (rayleigh + mie / 0.9 + absorption) / ln 2 per unit at 0
  glm::dvec3 camera_sun_depth_log2{};  // extinction_log2 sun_depth: A / ln 2 per channel
  // The sun's light in the sky: lighting's sun x intensity x the share of its disc above the
  // horizon x each coefficient x its phase function's constant.
  glm::dvec3 rayleigh_sun{}, mie_sun{};
  double mie_a = 1, mie_b = 0;  // 1 + g^2, 2 g
  // The sun's light that reaches the camera's height: lighting's sun x the disc's share above
  // the horizon x exp(-A) per channel. It lights the terrain and draws the disc.
  glm::dvec3 ground_sun{};
};

// `sun` is lighting's sun (colour x intensity), `elevation` and `disc_radius` in radians.
AtmospherePlan make_atmosphere_plan(const AtmosphereSettings& settings, double camera_y,
                                    double elevation, double disc_radius, const glm::dvec3& sun);

}  // namespace relief
