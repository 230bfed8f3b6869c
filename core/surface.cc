#include "core/surface.h"

#include <algorithm>
#include <cmath>

#include "core/limits.h"
#include "core/vertex_culling.h"

namespace relief {

namespace {

template <class Real>
struct Tangent {
  Real x = 0, h = 0, z = 0;
  bool present = false;
};

// Difference across vertex c along one grid axis: central where both neighbours are valid,
// one-sided otherwise. `minus`/`plus` are buffer indices or -1 outside the grid.
template <class Real>
Tangent<Real> axis_tangent(const SurfaceInputs<Real>& in, std::ptrdiff_t minus, std::size_t c,
                           std::ptrdiff_t plus) {
  const bool has_minus = minus >= 0 && in.valid[static_cast<std::size_t>(minus)];
  const bool has_plus = plus >= 0 && in.valid[static_cast<std::size_t>(plus)];
  const std::size_t from = has_minus ? static_cast<std::size_t>(minus) : c;
  const std::size_t to = has_plus ? static_cast<std::size_t>(plus) : c;
  Tangent<Real> t;
  t.present = has_minus || has_plus;
  if (t.present) {
    t.x = in.dx[to] - in.dx[from];
    t.h = in.height[to] - in.height[from];
    t.z = in.dz[to] - in.dz[from];
    // Scaled by the positive 1 / max(|x|, |h|, |z|): the normal's direction and the slope do
    // not change, but the products of four tangent components below stay near 1 whatever the
    // grid spacing (a scene scaled down to spacings of 1e-11 would underflow them to zero),
    // and no component exceeds 1. Division domain: largest > 0; a zero tangent stays zero.
    const Real largest = std::max({std::abs(t.x), std::abs(t.h), std::abs(t.z)});
    if (largest > Real(0)) {
      t.x = t.x / largest;
      t.h = t.h / largest;
      t.z = t.z / largest;
    }
  }
  return t;
}

}  // namespace

template <class Real>
void surface_pass(const SurfaceParams<Real>& p, RowRange rows, SurfaceInputs<Real> in,
                  SurfaceSpans<Real> out) {
  const GridLayout layout{p.width, p.height, p.pitch};
  const Real min_sine_sq = p.min_sine_sq;
  const Real water_level = p.water_level;  // heights are camera-relative
  const Real max_slope = p.max_slope;
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < layout.pitch; ++i) {
      const std::size_t k = layout.index(i, j);
      out.nx[k] = Real(0);
      out.ny[k] = Real(1);
      out.nz[k] = Real(0);
      out.slope[k] = Real(0);
      out.water_depth[k] = Real(0);
      if (i >= layout.width || !in.valid[k] || (!in.need.empty() && !(in.need[k] & kDraw))) {
        continue;
      }
      const auto index_or_none = [&](int ii, int jj) -> std::ptrdiff_t {
        if (ii < 0 || ii >= layout.width || jj < 0 || jj >= layout.height) {
          return -1;
        }
        return static_cast<std::ptrdiff_t>(layout.index(ii, jj));
      };
      const Tangent<Real> a = axis_tangent(in, index_or_none(i - 1, j), k, index_or_none(i + 1, j));
      const Tangent<Real> b = axis_tangent(in, index_or_none(i, j - 1), k, index_or_none(i, j + 1));
      // Unnormalised normal (-gx, 1, -gz) scaled by a positive factor: by |det| for the 2x2
      // solve (no division), by |a|^2 for the one-axis least-norm gradient.
      const Real a_sq = a.x * a.x + a.z * a.z;
      const Real b_sq = b.x * b.x + b.z * b.z;
      const Real det = a.x * b.z - a.z * b.x;
      Real nx = Real(0), ny = Real(1), nz = Real(0);
      if (a.present && b.present && det * det > min_sine_sq * a_sq * b_sq) {
        const Real sign = det > Real(0) ? Real(1) : Real(-1);
        nx = -(a.h * b.z - a.z * b.h) * sign;
        ny = det * sign;
        nz = -(a.x * b.h - a.h * b.x) * sign;
      } else if (a.present && a_sq > Real(0)) {
        nx = -a.h * a.x;
        ny = a_sq;
        nz = -a.h * a.z;
      } else if (b.present && b_sq > Real(0)) {
        nx = -b.h * b.x;
        ny = b_sq;
        nz = -b.h * b.z;
      }
      // Divide by the largest component first (> 0 because ny > 0) so that squaring cannot
      // overflow; the length is then in [1, sqrt 3].
      const Real largest = std::max({std::abs(nx), ny, std::abs(nz)});
      nx = nx / largest;
      ny = ny / largest;
      nz = nz / largest;
      const Real horizontal_sq = nx * nx + nz * nz;
      const Real inv_length = Real(1) / std::sqrt(horizontal_sq + ny * ny);
      out.nx[k] = nx * inv_length;
      out.ny[k] = ny * inv_length;
      out.nz[k] = nz * inv_length;
      // |g| = horizontal / ny; ny > 0 but may be tiny for a near-vertical cell.
      out.slope[k] = std::min(std::sqrt(horizontal_sq) / ny, max_slope);
      if (p.water_enabled) {
        out.water_depth[k] = std::max(Real(0), water_level - in.height[k]);
      }
    }
  }
}

template void surface_pass<float>(const SurfaceParams<float>&, RowRange, SurfaceInputs<float>,
                                  SurfaceSpans<float>);
template void surface_pass<double>(const SurfaceParams<double>&, RowRange, SurfaceInputs<double>,
                                   SurfaceSpans<double>);

}  // namespace relief
