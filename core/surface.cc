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

// Scales (x, h, z) by the positive 1 / max(|x|, |h|, |z|) where that is > 0: the direction is
// kept, every component is at most 1 in magnitude.
template <class Real>
void scale_to_unit_max(Real& x, Real& h, Real& z) {
  const Real largest = std::max({std::abs(x), std::abs(h), std::abs(z)});
  if (largest > Real(0)) {
    x = x / largest;
    h = h / largest;
    z = z / largest;
  }
}

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
    scale_to_unit_max(t.x, t.h, t.z);
  }
  return t;
}

// p[to] - p[from] as it is (for the weighted sum) and scaled to a largest component of 1 (for
// its side's facing weight, whatever the grid's spacing).
template <class Real>
struct SideDifference {
  Tangent<Real> raw, scaled;
};

template <class Real>
SideDifference<Real> side_difference(const SurfaceInputs<Real>& in, std::size_t from,
                                     std::size_t to) {
  SideDifference<Real> d;
  d.raw.x = in.dx[to] - in.dx[from];
  d.raw.h = in.height[to] - in.height[from];
  d.raw.z = in.dz[to] - in.dz[from];
  d.raw.present = true;
  d.scaled = d.raw;
  scale_to_unit_max(d.scaled.x, d.scaled.h, d.scaled.z);
  return d;
}

// The direction from the eye to the vertex (camera-relative position, scaled) and its length.
template <class Real>
struct EyeRay {
  Real x = 0, h = 0, z = 0, length = 0;
};

// How much the patch spanned by u (along the grid's i axis) and w (along j) faces the eye:
// min(max(cos / kSilhouetteFacing, kHiddenSideWeight), 1), cos between its upward normal and the
// direction to the eye (docs/architecture.md, "Stage 4, operation by operation"). 1 where the
// cosine is undefined (a patch or ray of zero length). Division domain: n_length * ray.length > 0.
template <class Real>
Real facing_weight(const Tangent<Real>& u, const Tangent<Real>& w, const EyeRay<Real>& ray,
                   Real inv_facing, Real least) {
  const Real nx = -(u.h * w.z - u.z * w.h);
  const Real ny = u.x * w.z - u.z * w.x;
  const Real nz = -(u.x * w.h - u.h * w.x);
  const Real sign = ny > Real(0) ? Real(1) : Real(-1);  // upward, as the vertex's normal
  const Real facing = -((nx * ray.x + ny * ray.h) + nz * ray.z) * sign;
  const Real length = std::sqrt((nx * nx + ny * ny) + nz * nz) * ray.length;
  if (!(length > Real(0))) {
    return Real(1);
  }
  const Real weight = (facing / length) * inv_facing;
  return weight < least ? least : (weight > Real(1) ? Real(1) : weight);
}

// A central difference's two halves weighted by their sides' facing weights (each in
// [kHiddenSideWeight, 1]) and summed as they are, then scaled: equal weights give the central
// difference's direction, so the result is continuous in the weights; unchanged where both
// weigh 1 (the plain central difference, bit for bit).
template <class Real>
void weigh_sides(Tangent<Real>& t, const SideDifference<Real>& minus, Real w_minus,
                 const SideDifference<Real>& plus, Real w_plus) {
  if (w_minus == Real(1) && w_plus == Real(1)) {
    return;
  }
  t.x = w_minus * minus.raw.x + w_plus * plus.raw.x;
  t.h = w_minus * minus.raw.h + w_plus * plus.raw.h;
  t.z = w_minus * minus.raw.z + w_plus * plus.raw.z;
  scale_to_unit_max(t.x, t.h, t.z);
}

// The visible sides of one axis: `t` reweighted from the vertices before and after c along
// it. `other` is the other axis's central tangent; the patch of a side is (side, other) along
// i and (other, side) along j.
template <class Real>
void weigh_axis(const SurfaceParams<Real>& p, const SurfaceInputs<Real>& in, std::size_t before,
                std::size_t c, std::size_t after, const Tangent<Real>& other, bool along_i,
                const EyeRay<Real>& ray, Tangent<Real>& t) {
  const SideDifference<Real> minus = side_difference(in, before, c);
  const SideDifference<Real> plus = side_difference(in, c, after);
  const auto weight = [&](const Tangent<Real>& side) {
    return along_i ? facing_weight(side, other, ray, p.inv_silhouette_facing, p.hidden_side_weight)
                   : facing_weight(other, side, ray, p.inv_silhouette_facing, p.hidden_side_weight);
  };
  weigh_sides(t, minus, weight(minus.scaled), plus, weight(plus.scaled));
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
      const std::ptrdiff_t left = index_or_none(i - 1, j), right = index_or_none(i + 1, j);
      const std::ptrdiff_t below = index_or_none(i, j - 1), above = index_or_none(i, j + 1);
      Tangent<Real> a = axis_tangent(in, left, k, right);
      Tangent<Real> b = axis_tangent(in, below, k, above);
      // Visible sides: each half of a central difference weighted by how much its side faces
      // the eye, both weights formed from the central tangents.
      const auto is_valid = [&](std::ptrdiff_t n) {
        return n >= 0 && in.valid[static_cast<std::size_t>(n)] != 0;
      };
      const bool a_central = is_valid(left) && is_valid(right);
      const bool b_central = is_valid(below) && is_valid(above);
      EyeRay<Real> ray{in.dx[k], in.height[k], in.dz[k]};
      scale_to_unit_max(ray.x, ray.h, ray.z);
      ray.length = std::sqrt((ray.x * ray.x + ray.h * ray.h) + ray.z * ray.z);
      if ((a_central || b_central) && ray.length > Real(0)) {
        Tangent<Real> weighted_a = a, weighted_b = b;
        if (a_central) {
          weigh_axis(p, in, static_cast<std::size_t>(left), k, static_cast<std::size_t>(right), b,
                     true, ray, weighted_a);
        }
        if (b_central) {
          weigh_axis(p, in, static_cast<std::size_t>(below), k, static_cast<std::size_t>(above), a,
                     false, ray, weighted_b);
        }
        a = weighted_a;
        b = weighted_b;
      }
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
