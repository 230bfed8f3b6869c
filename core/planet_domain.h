// Stage 2 on a planet (§4.1, docs/planet.md): the projected grid on the sphere, blended into
// equal-angle sampling from orbit. The same outputs as project_domain (projected_domain.h),
// with the footprint of each projector ray remapped onto the sphere:
//   alpha       the ray's nadir angle, atan2(horizontal, descent);
//   theta_true  the central angle of the ray's near hit with the grid sphere (plain projected
//               grid), t = c / (D cos alpha + sqrt(D^2 cos^2 alpha - c)) the stable root,
//               theta = atan2(t sin alpha, D - t cos alpha); the limb's angle where it misses;
//   theta_eq    theta_lo + eq_slope (alpha - alpha_lo): consecutive rows at equal angles;
//   theta       (1 - b) theta_true + b theta_eq, at least 0;
//   (dx, dz)    R theta times the ray's horizontal unit direction (an arc offset).
// Invalid: theta beyond theta_h (no landscape beyond the horizon), a ray that misses the
// sphere while b = 0, or a frame whose terrain cannot be seen. sigma and nu as project_domain,
// from the neighbours' remapped footprints.
#pragma once

#include "core/grid_buffers.h"
#include "core/planet_plan.h"
#include "core/stage_params.h"

namespace relief {

// Rows [rows.begin, rows.end) of `out`, as project_domain. The reference backends run this
// scalar code; the simd backend's Highway twin (simd/projected_domain.h) gives its bits.
template <class Real>
void project_planet_domain(const DomainParams<Real>& params, const PlanetParams<Real>& planet,
                           const DomainRows<Real>& rows_table, RowRange rows,
                           DomainSpans<Real> out);

// The arc offset (dx, dz) of the ray through image point (x, y) with descent `descent`; false
// (and zeros) where the vertex is invalid. Exposed for the tests.
template <class Real>
bool planet_footprint(const ProjectorRays<Real>& rays, const PlanetParams<Real>& planet, Real x,
                      Real y, Real descent, Real& dx, Real& dz);

}  // namespace relief
