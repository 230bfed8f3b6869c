// Per-target body of simd/projected_domain.h: core/projected_domain.cc with
// ProjectorRays::footprint (core/projector.cc), and core/planet_domain.cc with
// planet_footprint, per lane, a lane a column of a row; the scalar branches (a footprint off
// the plane, the sphere missed or too far, a missing neighbour, the log's domain) become masks
// and selections.
#if defined(RELIEF_SIMD_PROJECTED_DOMAIN_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PROJECTED_DOMAIN_INL_H_
#undef RELIEF_SIMD_PROJECTED_DOMAIN_INL_H_
#else
#define RELIEF_SIMD_PROJECTED_DOMAIN_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/planet_plan.h"
#include "core/stage_params.h"
#include "simd/det_math-inl.h"
#include "simd/det_trig-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

template <class D>
struct LaneFootprint {
  hn::Vec<D> x, z;
  hn::Mask<D> valid;
};

// ProjectorRays::footprint at image points (x, y) of one row (descent uniform).
template <class D, class V = hn::Vec<D>>
HWY_INLINE LaneFootprint<D> Footprint(D d, const DomainParams<float>& p, V x, float y,
                                      float descent) {
  const ProjectorRays<float>& r = p.rays;
  const V vy = hn::Set(d, y);
  const V ray_x = hn::Add(hn::Add(hn::Set(d, r.fx), hn::Mul(x, hn::Set(d, r.rx))),
                          hn::Mul(vy, hn::Set(d, r.ux)));
  const V ray_z = hn::Add(hn::Add(hn::Set(d, r.fz), hn::Mul(x, hn::Set(d, r.rz))),
                          hn::Mul(vy, hn::Set(d, r.uz)));
  const V horizontal_sq = hn::Add(hn::Mul(ray_x, ray_x), hn::Mul(ray_z, ray_z));
  const float min_descent = float(limits::kMinRayDescent);
  const V descent_sq = hn::Set(d, descent * descent);
  // descent^2 > min^2 (horizontal^2 + descent^2), and descent > 0 (uniform over the row).
  auto valid = hn::Gt(descent_sq, hn::Mul(hn::Set(d, min_descent * min_descent),
                                          hn::Add(horizontal_sq, descent_sq)));
  if (!(descent > 0.0f) || !p.terrain_visible) {
    valid = hn::FirstN(d, 0);
  }
  const V scale = hn::Set(d, r.height_above_plane / descent);
  const V px = hn::Mul(scale, ray_x);
  const V pz = hn::Mul(scale, ray_z);
  valid = hn::And(valid,
                  hn::Le(hn::Add(hn::Mul(px, px), hn::Mul(pz, pz)), hn::Set(d, r.max_distance_sq)));
  return {hn::IfThenElseZero(valid, px), hn::IfThenElseZero(valid, pz), valid};
}

// planet_footprint (core/planet_domain.cc) at image points (x, y) of one row (descent
// uniform): the ray's nadir angle, its near hit with the grid sphere (the limb's angle where
// it misses), the blend into equal-angle sampling, and the arc offset; invalid beyond the
// horizon, where the ray misses the sphere without the blend, or where `visible` is false.
template <class D, class V = hn::Vec<D>>
HWY_INLINE LaneFootprint<D> PlanetFootprint(D d, const DomainParams<float>& params,
                                            const PlanetParams<float>& p, bool visible, V x,
                                            float y, float descent) {
  const ProjectorRays<float>& r = params.rays;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V vy = hn::Set(d, y);
  const V ray_x = hn::Add(hn::Add(hn::Set(d, r.fx), hn::Mul(x, hn::Set(d, r.rx))),
                          hn::Mul(vy, hn::Set(d, r.ux)));
  const V ray_z = hn::Add(hn::Add(hn::Set(d, r.fz), hn::Mul(x, hn::Set(d, r.rz))),
                          hn::Mul(vy, hn::Set(d, r.uz)));
  const V horizontal = hn::Sqrt(hn::Add(hn::Mul(ray_x, ray_x), hn::Mul(ray_z, ray_z)));
  const V descent_v = hn::Set(d, descent);
  const V length =
      hn::Sqrt(hn::Add(hn::Mul(horizontal, horizontal), hn::Mul(descent_v, descent_v)));
  const auto has_length = hn::Gt(length, zero);  // the divisions' domain
  const V safe_length = hn::IfThenElse(has_length, length, one);
  const V cos_a = hn::Div(descent_v, safe_length);
  const V sin_a = hn::Div(horizontal, safe_length);
  const V center = hn::Set(d, p.center_distance);
  const V grid_c = hn::Set(d, p.grid_c);
  const V dc = hn::Mul(center, cos_a);
  const V disc = hn::Sub(hn::Mul(dc, dc), grid_c);
  const auto hit = hn::And(hn::Gt(cos_a, zero), hn::Ge(disc, zero));
  // Domain: dc > 0 and c > 0 where it hits; the other lanes divide by 1 and discard it.
  const V denominator =
      hn::IfThenElse(hit, hn::Add(dc, hn::Sqrt(hn::IfThenElseZero(hit, disc))), one);
  const V t = hn::Div(grid_c, denominator);
  const V theta_hit = Atan2Lanes(d, hn::Mul(t, sin_a), hn::Sub(center, hn::Mul(t, cos_a)));
  const V theta_true = hn::IfThenElse(hit, theta_hit, hn::Set(d, p.theta_limb));
  const V alpha = Atan2Lanes(d, horizontal, descent_v);
  const V theta_eq =
      hn::Add(hn::Set(d, p.theta_lo),
              hn::Mul(hn::Set(d, p.eq_slope), hn::Sub(alpha, hn::Set(d, p.alpha_lo))));
  const V mixed = hn::Add(hn::Mul(hn::Set(d, p.one_minus_blend), theta_true),
                          hn::Mul(hn::Set(d, p.blend), theta_eq));
  const V theta = hn::IfThenElse(hn::Lt(zero, mixed), mixed, zero);  // std::max(0, mixed)
  auto valid = hn::And(has_length, hn::Le(theta, hn::Set(d, p.theta_h)));
  if (!(p.blend > 0.0f)) {
    valid = hn::And(valid, hit);
  }
  if (!visible) {
    valid = hn::FirstN(d, 0);
  }
  // Straight down the direction is undefined and theta 0: (0, 0). Domain: horizontal > 0.
  const auto level = hn::Gt(horizontal, zero);
  const V scale =
      hn::Div(hn::Mul(hn::Set(d, p.radius), theta), hn::IfThenElse(level, horizontal, one));
  const auto placed = hn::And(valid, level);
  return {hn::IfThenElseZero(placed, hn::Mul(scale, ray_x)),
          hn::IfThenElseZero(placed, hn::Mul(scale, ray_z)), valid};
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V DistanceSq(const LaneFootprint<D>& a, const LaneFootprint<D>& b) {
  const V ex = hn::Sub(a.x, b.x);
  const V ez = hn::Sub(a.z, b.z);
  return hn::Add(hn::Mul(ex, ex), hn::Mul(ez, ez));
}

// axis_spacing_sq (projected_domain.cc): both neighbours, then the plus one, then the minus one.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V AxisSpacingSq(D d, const LaneFootprint<D>& minus, const LaneFootprint<D>& centre,
                           const LaneFootprint<D>& plus) {
  V result = hn::IfThenElseZero(minus.valid, DistanceSq(minus, centre));
  result = hn::IfThenElse(plus.valid, DistanceSq(centre, plus), result);
  return hn::IfThenElse(hn::And(minus.valid, plus.valid),
                        hn::Mul(DistanceSq(minus, plus), hn::Set(d, 0.25f)), result);
}

// project_domain_rows (core/projected_domain_rows.h) with `footprint(d, x, y, descent)` the
// lanes' ray footprints: the plane's or the sphere's.
template <class FootprintOf>
HWY_INLINE void ProjectRows(const DomainParams<float>& p, const DomainRows<float>& table,
                            RowRange rows, DomainSpans<float> out, FootprintOf footprint) {
  hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const V one = hn::Set(d, 1.0f);
  const V nu_max = hn::Set(d, p.nu_max);
  for (int j = rows.begin; j < rows.end; ++j) {
    const auto row = static_cast<std::size_t>(j + 1);  // the table starts at row -1
    const float y_here = p.y0 + float(j) * p.step_y;
    const float y_below = p.y0 + float(j - 1) * p.step_y;
    const float y_above = p.y0 + float(j + 1) * p.step_y;
    for (int i = 0; i < p.pitch; i += lanes) {
      const std::size_t k = static_cast<std::size_t>(j) * p.pitch + i;
      const auto column = hn::Iota(di, i);
      // Image x of columns i - 1, i, i + 1 in row j, and of column i in rows j -+ 1.
      const auto x_of = [&](std::size_t r, int shift) {
        const V ci = hn::ConvertTo(d, hn::Add(column, hn::Set(di, shift)));
        return hn::Add(hn::Set(d, table.x0[r]), hn::Mul(ci, hn::Set(d, table.step_x[r])));
      };
      const auto inside = hn::RebindMask(d, hn::Lt(column, hn::Set(di, p.width)));
      const auto centre = footprint(d, x_of(row, 0), y_here, table.descent[row]);
      const auto valid = hn::And(inside, centre.valid);
      V dx = hn::Zero(d), dz = hn::Zero(d), sigma = hn::Zero(d), nu = one;
      if (!hn::AllFalse(d, valid)) {
        const auto left = footprint(d, x_of(row, -1), y_here, table.descent[row]);
        const auto right = footprint(d, x_of(row, 1), y_here, table.descent[row]);
        const auto below = footprint(d, x_of(row - 1, 0), y_below, table.descent[row - 1]);
        const auto above = footprint(d, x_of(row + 1, 0), y_above, table.descent[row + 1]);
        const V along = AxisSpacingSq(d, left, centre, right);
        const V across = AxisSpacingSq(d, below, centre, above);
        // std::max(along, across): along < across ? across : along.
        const V spacing_sq = hn::IfThenElse(hn::Lt(along, across), across, along);
        // std::clamp(c0 - c1 log2_det(s), 1, nu_max) where s > min_spacing_sq; nu_max else.
        const V raw = hn::Sub(hn::Set(d, p.c0), hn::Mul(hn::Set(d, p.c1), Log2Det(d, spacing_sq)));
        const V clamped =
            hn::IfThenElse(hn::Lt(raw, one), one, hn::IfThenElse(hn::Lt(nu_max, raw), nu_max, raw));
        V lod = hn::IfThenElse(hn::Gt(spacing_sq, hn::Set(d, p.min_spacing_sq)), clamped, nu_max);
        if (p.whole_octaves != 0) {
          lod = hn::Ceil(lod);  // std::ceil: exact on every target for 1 <= lod <= nu_max
        }
        dx = hn::IfThenElseZero(valid, centre.x);
        dz = hn::IfThenElseZero(valid, centre.z);
        sigma = hn::IfThenElseZero(valid, hn::Sqrt(spacing_sq));
        nu = hn::IfThenElse(valid, lod, one);
      }
      hn::StoreU(dx, d, out.dx.data() + k);
      hn::StoreU(dz, d, out.dz.data() + k);
      hn::StoreU(sigma, d, out.sigma.data() + k);
      hn::StoreU(nu, d, out.nu.data() + k);
      const auto flags = hn::IfThenElseZero(hn::RebindMask(di, valid), hn::Set(di, 1));
      hn::StoreU(hn::DemoteTo(d8, flags), d8, out.valid.data() + k);
    }
  }
}

void ProjectDomainRows(const DomainParams<float>& p, const DomainRows<float>& table, RowRange rows,
                       DomainSpans<float> out) {
  ProjectRows(p, table, rows, out, [&](auto d, auto x, float y, float descent) {
    return Footprint(d, p, x, y, descent);
  });
}

void ProjectPlanetDomainRows(const DomainParams<float>& p, const PlanetParams<float>& planet,
                             const DomainRows<float>& table, RowRange rows,
                             DomainSpans<float> out) {
  const bool visible = p.terrain_visible != 0 && planet.visible != 0;
  ProjectRows(p, table, rows, out, [&](auto d, auto x, float y, float descent) {
    return PlanetFootprint(d, p, planet, visible, x, y, descent);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
