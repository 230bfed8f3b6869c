// Stage 2's vertex loop and its local grid spacing sigma (§4.1's LOD), shared by the plane
// (projected_domain.cc) and the sphere (planet_domain.cc): sigma is the half distance between a
// vertex's two neighbours' footprints along one grid axis, one-sided where a neighbour is
// invalid.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/det_math.h"
#include "core/grid_buffers.h"
#include "core/lod_rule.h"
#include "core/stage_params.h"

namespace relief {

template <class Real>
struct Footprint {
  Real x = 0;
  Real z = 0;
  bool valid = false;
};

template <class Real>
Real footprint_distance_sq(const Footprint<Real>& a, const Footprint<Real>& b) {
  const Real ex = a.x - b.x;
  const Real ez = a.z - b.z;
  return ex * ex + ez * ez;
}

// Squared spacing along one grid axis from the centre and its two neighbours.
template <class Real>
Real axis_spacing_sq(const Footprint<Real>& minus, const Footprint<Real>& centre,
                     const Footprint<Real>& plus) {
  if (minus.valid && plus.valid) {
    return footprint_distance_sq(minus, plus) * Real(0.25);
  }
  if (plus.valid) {
    return footprint_distance_sq(centre, plus);
  }
  if (minus.valid) {
    return footprint_distance_sq(minus, centre);
  }
  return Real(0);
}

// Stage 2's row loop (§4.1's LOD paragraph), the plane's and the sphere's: every entry of rows
// [rows.begin, rows.end) written (padding and invalid vertices dx = dz = sigma = 0, nu = 1,
// valid = 0), each valid vertex's footprint, spacing sigma and octave count nu. `visible`:
// false leaves every vertex invalid; `ray_footprint(x, y, descent, dx, dz)` the footprint of the
// ray through image point (x, y) (ProjectorRays::footprint, or planet_footprint), false where
// there is none.
template <class Real, class RayFootprint>
void project_domain_rows(const DomainParams<Real>& p, const DomainRows<Real>& table, RowRange rows,
                         DomainSpans<Real> out, bool visible, RayFootprint ray_footprint) {
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
    f.valid = visible && ray_footprint(r.x0 + Real(i) * r.step_x, p.y0 + Real(j) * p.step_y,
                                       r.descent, f.x, f.z);
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
      Real nu = lod_octave_count(p.c0, p.c1, p.nu_max, p.min_spacing_sq, spacing_sq);
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

}  // namespace relief
