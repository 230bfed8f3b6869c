#include "core/projected_domain.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/footprint_spacing.h"
#include "core/limits.h"

namespace relief {

template <class Real>
void project_domain(const DomainParams<Real>& p, const DomainRows<Real>& table, RowRange rows,
                    DomainSpans<Real> out) {
  // Per-row values formed in double (projector.h, screen_grid.h explain why), for rows j - 1,
  // j, j + 1: the ray descent and the row's column placement.
  struct Row {
    Real descent, x0, step_x;
  };
  auto row = [&](int j) {
    const auto k = static_cast<std::size_t>(j + 1);
    return Row{table.descent[k], table.x0[k], table.step_x[k]};
  };
  auto footprint = [&](int i, int j, const Row& r) {
    Footprint<Real> f;
    f.valid = p.terrain_visible && p.rays.footprint(r.x0 + Real(i) * r.step_x,
                                                    p.y0 + Real(j) * p.step_y, r.descent, f.x, f.z);
    return f;
  };
  for (int j = rows.begin; j < rows.end; ++j) {
    const Row below = row(j - 1), here = row(j), above = row(j + 1);
    for (int i = 0; i < p.pitch; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * p.pitch + i;
      out.dx[k] = Real(0);
      out.dz[k] = Real(0);
      out.sigma[k] = Real(0);
      out.nu[k] = Real(1);
      out.valid[k] = 0;
      if (i >= p.width) {
        continue;
      }
      const Footprint<Real> centre = footprint(i, j, here);
      if (!centre.valid) {
        continue;
      }
      const Real spacing_sq =
          std::max(axis_spacing_sq(footprint(i - 1, j, here), centre, footprint(i + 1, j, here)),
                   axis_spacing_sq(footprint(i, j - 1, below), centre, footprint(i, j + 1, above)));
      Real nu = p.nu_max;
      if (spacing_sq > p.min_spacing_sq) {
        nu = std::clamp(p.c0 - p.c1 * log2_det(spacing_sq), Real(1), p.nu_max);
      }
      if (p.whole_octaves != 0) {
        nu = std::ceil(nu);  // nu_max is whole: still within [1, nu_max]
      }
      out.dx[k] = centre.x;
      out.dz[k] = centre.z;
      out.sigma[k] = std::sqrt(spacing_sq);
      out.nu[k] = nu;
      out.valid[k] = 1;
    }
  }
}

template void project_domain<float>(const DomainParams<float>&, const DomainRows<float>&, RowRange,
                                    DomainSpans<float>);
template void project_domain<double>(const DomainParams<double>&, const DomainRows<double>&,
                                     RowRange, DomainSpans<double>);

}  // namespace relief
