#include "core/planet_bend.h"

#include <cmath>

#include "core/det_math.h"

namespace relief {

template <class Real>
void bend_vertices(const PlanetParams<Real>& p, IndexRange range, std::span<const Real> dx,
                   std::span<const Real> dz, std::span<const Real> height,
                   std::span<const std::uint8_t> valid, BentSpans<Real> out) {
  for (std::size_t k = range.begin; k < range.end; ++k) {
    out.x[k] = Real(0);
    out.y[k] = Real(0);
    out.z[k] = Real(0);
    out.drop[k] = Real(0);
    if (!valid[k]) {
      continue;
    }
    const Real rho = std::sqrt(dx[k] * dx[k] + dz[k] * dz[k]);
    const Real theta = rho * p.inv_radius;
    Real sine, cosine;
    sin_cos_det(theta, sine, cosine);
    // sinc: 1 at 0 (the limit); domain of the division: theta > 0.
    const Real sinc = theta > Real(0) ? sine / theta : Real(1);
    const Real half_sine = sin_det(theta * Real(0.5));
    const Real radius_here = p.center_distance + height[k];  // R + e
    const Real scale = radius_here * p.inv_radius * sinc;
    const Real drop = radius_here * (Real(2) * half_sine * half_sine);
    out.x[k] = dx[k] * scale;
    out.z[k] = dz[k] * scale;
    out.y[k] = height[k] - drop;
    out.drop[k] = drop;
  }
}

template <class Real>
void bend_normals(const PlanetParams<Real>& p, IndexRange range, std::span<const Real> dx,
                  std::span<const Real> dz, std::span<const std::uint8_t> valid, std::span<Real> nx,
                  std::span<Real> ny, std::span<Real> nz) {
  for (std::size_t k = range.begin; k < range.end; ++k) {
    const Real rho = std::sqrt(dx[k] * dx[k] + dz[k] * dz[k]);
    if (!valid[k] || !(rho > Real(0))) {
      continue;  // the nadir's frame is the camera's
    }
    const Real theta = rho * p.inv_radius;
    const Real sine = sin_det(theta);
    const Real half_sine = sin_det(theta * Real(0.5));
    const Real cos_minus_one = Real(-2) * half_sine * half_sine;  // no cancellation near 0
    const Real ux = dx[k] / rho, uz = dz[k] / rho;                // domain: rho > 0
    const Real along = nx[k] * ux + nz[k] * uz;
    const Real n_y = ny[k];
    const Real delta = along * cos_minus_one + n_y * sine;  // the change of the along part
    nx[k] = nx[k] + delta * ux;
    nz[k] = nz[k] + delta * uz;
    ny[k] = n_y + n_y * cos_minus_one - along * sine;
  }
}

template void bend_vertices<float>(const PlanetParams<float>&, IndexRange, std::span<const float>,
                                   std::span<const float>, std::span<const float>,
                                   std::span<const std::uint8_t>, BentSpans<float>);
template void bend_vertices<double>(const PlanetParams<double>&, IndexRange,
                                    std::span<const double>, std::span<const double>,
                                    std::span<const double>, std::span<const std::uint8_t>,
                                    BentSpans<double>);
template void bend_normals<float>(const PlanetParams<float>&, IndexRange, std::span<const float>,
                                  std::span<const float>, std::span<const std::uint8_t>,
                                  std::span<float>, std::span<float>, std::span<float>);
template void bend_normals<double>(const PlanetParams<double>&, IndexRange, std::span<const double>,
                                   std::span<const double>, std::span<const std::uint8_t>,
                                   std::span<double>, std::span<double>, std::span<double>);

}  // namespace relief
