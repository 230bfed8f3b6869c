#include "core/projected_domain.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/limits.h"

namespace relief {

namespace {

template <class Real>
struct Footprint {
  Real x = 0;
  Real z = 0;
  bool valid = false;
};

template <class Real>
Real distance_sq(const Footprint<Real>& a, const Footprint<Real>& b) {
  const Real ex = a.x - b.x;
  const Real ez = a.z - b.z;
  return ex * ex + ez * ez;
}

// Squared spacing along one grid axis from the centre and its two neighbours.
template <class Real>
Real axis_spacing_sq(const Footprint<Real>& minus, const Footprint<Real>& centre,
                     const Footprint<Real>& plus) {
  if (minus.valid && plus.valid) {
    return distance_sq(minus, plus) * Real(0.25);
  }
  if (plus.valid) {
    return distance_sq(centre, plus);
  }
  if (minus.valid) {
    return distance_sq(minus, centre);
  }
  return Real(0);
}

}  // namespace

template <class Real>
void project_domain(const FramePlan& plan, RowRange rows, DomainSpans<Real> out) {
  const ProjectorRays<Real> rays(plan.projector);
  const ScreenGrid& screen = plan.screen;
  const GridLayout& layout = plan.layout;
  const Real x0 = Real(screen.x0), step_x = Real(screen.step_x);
  const Real y0 = Real(screen.y0), step_y = Real(screen.step_y);
  const Real c0 = Real(plan.lod.c0), c1 = Real(plan.lod.c1), nu_max = Real(plan.lod.nu_max);
  const Real min_spacing_sq = Real(limits::kMinSpacingSq);
  // Per-row ray descents in double (projector.h explains why), for rows j - 1, j, j + 1.
  auto descent = [&](int j) { return Real(projector_descent(plan.projector, screen.image_y(j))); };
  auto footprint = [&](int i, int j, Real row_descent) {
    Footprint<Real> f;
    f.valid = plan.projector.terrain_visible &&
              rays.footprint(x0 + Real(i) * step_x, y0 + Real(j) * step_y, row_descent, f.x, f.z);
    return f;
  };
  for (int j = rows.begin; j < rows.end; ++j) {
    const Real below = descent(j - 1), here = descent(j), above = descent(j + 1);
    for (int i = 0; i < layout.pitch; ++i) {
      const std::size_t k = layout.index(i, j);
      out.dx[k] = Real(0);
      out.dz[k] = Real(0);
      out.sigma[k] = Real(0);
      out.nu[k] = Real(1);
      out.valid[k] = 0;
      if (i >= layout.width) {
        continue;
      }
      const Footprint<Real> centre = footprint(i, j, here);
      if (!centre.valid) {
        continue;
      }
      const Real spacing_sq =
          std::max(axis_spacing_sq(footprint(i - 1, j, here), centre, footprint(i + 1, j, here)),
                   axis_spacing_sq(footprint(i, j - 1, below), centre, footprint(i, j + 1, above)));
      Real nu = nu_max;
      if (spacing_sq > min_spacing_sq) {
        nu = std::clamp(c0 - c1 * log2_det(spacing_sq), Real(1), nu_max);
      }
      out.dx[k] = centre.x;
      out.dz[k] = centre.z;
      out.sigma[k] = std::sqrt(spacing_sq);
      out.nu[k] = nu;
      out.valid[k] = 1;
    }
  }
}

template void project_domain<float>(const FramePlan&, RowRange, DomainSpans<float>);
template void project_domain<double>(const FramePlan&, RowRange, DomainSpans<double>);

}  // namespace relief
