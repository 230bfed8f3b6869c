#include "core/planet_plan.h"

#include <algorithm>
#include <cmath>

#include "core/limits.h"

namespace relief {

namespace {

// The projector's clearance below a camera that is under the base height (projector.cc).
double projector_clearance(const CameraFrame& camera, const HeightBounds& bounds) {
  return std::max(camera.near, 0.01 * (bounds.world_max - bounds.world_min));
}

double nadir_angle(const glm::dvec3& ray) {
  return std::atan2(std::hypot(ray.x, ray.z), -ray.y);  // in [0, pi]
}

// Whether q lies inside the counter-clockwise convex polygon `hull`.
bool inside(const std::vector<glm::dvec2>& hull, const glm::dvec2& q) {
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 a = hull[i];
    const glm::dvec2 b = hull[(i + 1) % hull.size()];
    if ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x) < 0.0) {
      return false;
    }
  }
  return !hull.empty();
}

// The smallest nadir angle of the rays through the coverage hull: 0 when the nadir's image
// lies inside it, else the least over its boundary (sampled finely: the angle along an edge
// has one minimum, which may lie between the corners).
double smallest_nadir_angle(const Projector& p) {
  const double depth = -p.forward.y;  // the nadir (0, -1, 0) along the projector's axis
  if (depth > 0.0 && inside(p.hull, glm::dvec2(-p.right.y / depth, -p.up.y / depth))) {
    return 0.0;
  }
  constexpr int kSamples = 64;
  double least = M_PI;
  for (std::size_t i = 0; i < p.hull.size(); ++i) {
    const glm::dvec2 a = p.hull[i];
    const glm::dvec2 b = p.hull[(i + 1) % p.hull.size()];
    for (int s = 0; s < kSamples; ++s) {
      const glm::dvec2 q = a + (b - a) * (double(s) / kSamples);
      least = std::min(least, nadir_angle(p.forward + q.x * p.right + q.y * p.up));
    }
  }
  return least;
}

}  // namespace

PlanetPlan make_planet_plan(const TerrainSettings& terrain, const CameraFrame& camera,
                            const HeightBounds& bounds) {
  PlanetPlan plan;
  if (!terrain.planet || terrain.planet->radius == 0.0) {
    return plan;
  }
  const PlanetSettings& s = *terrain.planet;
  const double R = s.radius;
  plan.enabled = true;
  plan.radius = R;
  plan.altitude = camera.position.y - terrain.base_height;
  plan.center_distance = R + plan.altitude;
  plan.elevation_min = bounds.world_min - terrain.base_height;
  plan.elevation_max = bounds.world_max - terrain.base_height;
  const double a = plan.altitude;
  const double e_lo = plan.elevation_min, e_hi = plan.elevation_max;
  // The camera below every terrain (or below the centre): nothing to draw, all finite.
  if (!(a > e_lo) || !(plan.center_distance > 0.5 * R)) {
    return plan;
  }
  // The grid sphere: the datum, or just below a camera that is under it (projector.cc's plane).
  const double clearance = projector_clearance(camera, bounds);
  const double ag = a >= clearance ? a : clearance;
  plan.grid_radius = plan.center_distance - ag;
  if (!(plan.grid_radius > 0.5 * R)) {
    return plan;
  }
  plan.grid_c = ag * (2.0 * plan.grid_radius + ag);
  plan.theta_limb = std::atan2(std::sqrt(plan.grid_c), plan.grid_radius);
  plan.alpha_h = std::atan2(plan.grid_radius, std::sqrt(plan.grid_c));
  // Terrain can be seen up to the camera's horizon over the lowest terrain plus the highest
  // terrain's horizon over it: acos(R_lo / D) + acos(R_lo / (R + e_max)), R_lo = R + e_min,
  // each written without cancellation as atan2(sqrt((x - R_lo)(x + R_lo)), R_lo).
  // A relief deeper than the radius would put R_lo at or below the centre: the bound is kept
  // at R / 2 (the horizon then errs on the far side: more terrain, never less).
  const double r_lo = std::max(R + e_lo, 0.5 * R);
  // (D - R_lo) >= a - e_lo > 0 and (R + e_max - R_lo) >= 0 whichever R_lo the guard chose.
  const double camera_side =
      std::atan2(std::sqrt((plan.center_distance - r_lo) * (plan.center_distance + r_lo)), r_lo);
  const double terrain_side =
      std::atan2(std::sqrt(std::max(0.0, R + e_hi - r_lo) * (R + e_hi + r_lo)), r_lo);
  double theta_h = std::min(camera_side + terrain_side, limits::kMaxPlanetAngle);
  if (s.horizon > 0.0) {
    theta_h = std::min(theta_h, s.horizon / R);  // the artificial horizon
  }
  plan.theta_h = theta_h;
  if (s.equal_angle) {
    const double begin = (*s.equal_angle)[0], end = (*s.equal_angle)[1];
    const double t = std::clamp((a - begin) / (end - begin), 0.0, 1.0);  // end > begin
    plan.blend = t * t * (3.0 - 2.0 * t);
  }
  plan.visible = true;
  return plan;
}

double planet_theta_true(const PlanetPlan& p, double alpha) {
  const double cos_a = std::cos(alpha), sin_a = std::sin(alpha);
  const double dc = p.center_distance * cos_a;
  const double disc = dc * dc - p.grid_c;
  if (!(cos_a > 0.0) || !(disc >= 0.0)) {
    return p.theta_limb;
  }
  const double t = p.grid_c / (dc + std::sqrt(disc));
  return std::atan2(t * sin_a, p.center_distance - t * cos_a);
}

namespace {

// The blended central angle of stage 2 (planet_domain.h) in double.
double blended_theta(const PlanetPlan& planet, double slope, double alpha) {
  const double theta_eq = planet.theta_lo + slope * (alpha - planet.alpha_lo);
  return (1.0 - planet.blend) * planet_theta_true(planet, alpha) + planet.blend * theta_eq;
}

// Points on the rays that extend the coverage hull toward the nadir where equal-angle
// sampling needs them (docs/planet.md, "Coverage"): theta_eq lies above theta_true (a chord of
// a convex function), so a ray of nadir angle alpha on the hull's boundary puts its vertex
// beyond the terrain the ray sees, theta_true(alpha). The ray of the same azimuth whose
// blended theta is theta_true(alpha) (nadir angle alpha_s <= alpha, found by bisection: the
// blend increases with alpha) is added, so that every azimuth of the hull is covered from its
// true near hit on. alpha_s moves continuously with the blend and equals alpha at b = 0: the
// grid does not jump where the band begins. Points are footprints on the projection plane
// `height` below the camera.
void append_equal_angle_extension(const Projector& p, const PlanetPlan& planet, double slope,
                                  double height, std::vector<glm::dvec3>& points) {
  constexpr int kSamples = 64;
  for (std::size_t i = 0; i < p.hull.size(); ++i) {
    const glm::dvec2 a = p.hull[i];
    const glm::dvec2 b = p.hull[(i + 1) % p.hull.size()];
    for (int s = 0; s < kSamples; ++s) {
      const glm::dvec2 q = a + (b - a) * (double(s) / kSamples);
      const glm::dvec3 ray = p.forward + q.x * p.right + q.y * p.up;
      const double horizontal = std::hypot(ray.x, ray.z);
      const double alpha = nadir_angle(ray);
      if (!(alpha < planet.alpha_h) || !(horizontal > 0.0)) {
        continue;
      }
      const double theta = planet_theta_true(planet, alpha);
      double lo = 0.0, hi = alpha;  // blended_theta(hi) >= theta
      for (int step = 0; step < 48; ++step) {
        const double mid = 0.5 * (lo + hi);
        (blended_theta(planet, slope, mid) < theta ? lo : hi) = mid;
      }
      const double alpha_s = hi;
      if (!(alpha_s < alpha)) {
        continue;
      }
      // The footprint of the ray (azimuth of `ray`, nadir angle alpha_s < pi/2).
      const double reach = height * std::tan(alpha_s);
      points.emplace_back(reach * ray.x / horizontal, -height, reach * ray.z / horizontal);
    }
  }
}

}  // namespace

Projector make_planet_projector(const CameraFrame& camera, const HeightBounds& bounds,
                                double base_height, PlanetPlan& planet) {
  if (!planet.visible) {
    return Projector{};
  }
  // Bent terrain at central angle theta <= theta_h lies (R + e)(1 - cos theta) below its
  // planar height. No regional refinement: its regions are planar.
  const double y_lo = bounds.world_min - camera.position.y -
                      (planet.radius + planet.elevation_max) * (1.0 - std::cos(planet.theta_h));
  std::vector<glm::dvec3> points =
      frustum_slab_vertices(camera, y_lo, bounds.world_max - camera.position.y);
  if (points.empty()) {
    planet.visible = false;
    return Projector{};
  }
  // The projection plane as make_projector places it.
  const double plane_y =
      std::min(base_height - camera.position.y, -projector_clearance(camera, bounds));
  const Projector first = fit_projector_to_points(camera, points, -plane_y);
  // Rays past the limb map beyond theta_h in equal-angle mode; keep alpha_lo below alpha_h.
  planet.alpha_lo = std::min(smallest_nadir_angle(first), planet.alpha_h * (1.0 - 1e-6));
  planet.theta_lo = planet_theta_true(planet, planet.alpha_lo);
  if (!(planet.blend > 0.0)) {
    return first;
  }
  const double slope = (planet.theta_h - planet.theta_lo) / (planet.alpha_h - planet.alpha_lo);
  if (!(slope > 0.0)) {
    return first;
  }
  append_equal_angle_extension(first, planet, slope, -plane_y, points);
  return fit_projector_to_points(camera, points, -plane_y);
}

template <class Real>
PlanetParams<Real> make_planet_params(const PlanetPlan& plan) {
  PlanetParams<Real> p;
  p.enabled = plan.enabled ? 1 : 0;
  p.visible = plan.visible ? 1 : 0;
  if (!plan.enabled) {
    return p;
  }
  p.radius = Real(plan.radius);
  p.inv_radius = Real(1.0 / plan.radius);
  p.center_distance = Real(plan.center_distance);
  p.grid_c = Real(plan.grid_c);
  p.blend = Real(plan.blend);
  p.one_minus_blend = Real(1.0 - plan.blend);
  p.theta_h = Real(plan.theta_h);
  p.theta_limb = Real(plan.theta_limb);
  p.alpha_lo = Real(plan.alpha_lo);
  p.theta_lo = Real(plan.theta_lo);
  // Domain: alpha_lo <= alpha_h (1 - 1e-6) < alpha_h when visible.
  const double span = plan.alpha_h - plan.alpha_lo;
  p.eq_slope = plan.visible && span > 0.0 ? Real((plan.theta_h - plan.theta_lo) / span) : Real(0);
  return p;
}

template PlanetParams<float> make_planet_params<float>(const PlanetPlan&);
template PlanetParams<double> make_planet_params<double>(const PlanetPlan&);

}  // namespace relief
