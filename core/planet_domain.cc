#include "core/planet_domain.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/limits.h"
#include "core/projected_domain_rows.h"

namespace relief {

template <class Real>
bool planet_footprint(const ProjectorRays<Real>& r, const PlanetParams<Real>& p, Real x, Real y,
                      Real descent, Real& dx, Real& dz) {
  dx = Real(0);
  dz = Real(0);
  // The projector has no roll: x does not change ray.y (projector.h).
  const Real ray_x = r.fx + x * r.rx + y * r.ux;
  const Real ray_z = r.fz + x * r.rz + y * r.uz;
  const Real horizontal = std::sqrt(ray_x * ray_x + ray_z * ray_z);
  const Real length = std::sqrt(horizontal * horizontal + descent * descent);
  if (!(length > Real(0))) {
    return false;  // the division's domain below; never for a projector ray
  }
  const Real cos_a = descent / length;
  const Real sin_a = horizontal / length;
  // The plain projected grid on the sphere: the ray's near hit with the grid sphere.
  const Real dc = p.center_distance * cos_a;
  const Real disc = dc * dc - p.grid_c;
  const bool hit = cos_a > Real(0) && disc >= Real(0);
  Real theta_true = p.theta_limb;
  if (hit) {
    // Domain: dc > 0 and c > 0, so the denominator is positive and t in (0, D cos alpha].
    const Real t = p.grid_c / (dc + std::sqrt(disc));
    theta_true = atan2_det(t * sin_a, p.center_distance - t * cos_a);
  }
  const Real alpha = atan2_det(horizontal, descent);
  const Real theta_eq = p.theta_lo + p.eq_slope * (alpha - p.alpha_lo);
  const Real theta = std::max(Real(0), p.one_minus_blend * theta_true + p.blend * theta_eq);
  if (!(theta <= p.theta_h) || (!hit && !(p.blend > Real(0)))) {
    return false;
  }
  // Straight down the direction is undefined and theta is 0: (0, 0). Domain of the division:
  // horizontal > 0.
  if (horizontal > Real(0)) {
    const Real scale = p.radius * theta / horizontal;
    dx = scale * ray_x;
    dz = scale * ray_z;
  }
  return true;
}

template <class Real>
void project_planet_domain(const DomainParams<Real>& p, const PlanetParams<Real>& planet,
                           const DomainRows<Real>& table, RowRange rows, DomainSpans<Real> out) {
  project_domain_rows(p, table, rows, out, p.terrain_visible != 0 && planet.visible != 0,
                      [&](Real x, Real y, Real descent, Real& dx, Real& dz) {
                        return planet_footprint(p.rays, planet, x, y, descent, dx, dz);
                      });
}

template bool planet_footprint<float>(const ProjectorRays<float>&, const PlanetParams<float>&,
                                      float, float, float, float&, float&);
template bool planet_footprint<double>(const ProjectorRays<double>&, const PlanetParams<double>&,
                                       double, double, double, double&, double&);
template void project_planet_domain<float>(const DomainParams<float>&, const PlanetParams<float>&,
                                           const DomainRows<float>&, RowRange, DomainSpans<float>);
template void project_planet_domain<double>(const DomainParams<double>&,
                                            const PlanetParams<double>&, const DomainRows<double>&,
                                            RowRange, DomainSpans<double>);

}  // namespace relief
