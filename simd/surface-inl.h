// Per-target body of simd/surface.h: core/surface.cc per lane, a lane a vertex of a row. The
// scalar branches become selections: a missing neighbour is the vertex itself (a zero
// difference), std::max and std::min of finite values keep their argument order.
#if defined(RELIEF_SIMD_SURFACE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SURFACE_INL_H_
#undef RELIEF_SIMD_SURFACE_INL_H_
#else
#define RELIEF_SIMD_SURFACE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/grid_buffers.h"
#include "core/stage_params.h"
#include "core/surface.h"
#include "core/vertex_culling.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

template <class D>
struct LaneTangent {
  hn::Vec<D> x, h, z;
  hn::Mask<D> present;
};

template <class D>
struct RowView {
  const float* dx;
  const float* dz;
  const float* height;
};

// (x, h, z) scaled by 1 / max(|x|, |h|, |z|) where that is > 0 (core/surface.cc,
// scale_to_unit_max).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void ScaleToUnitMax(D d, V& x, V& h, V& z) {
  const V largest = hn::Max(hn::Max(hn::Abs(x), hn::Abs(h)), hn::Abs(z));
  const auto scale = hn::Gt(largest, hn::Zero(d));
  x = hn::IfThenElse(scale, hn::Div(x, largest), x);
  h = hn::IfThenElse(scale, hn::Div(h, largest), h);
  z = hn::IfThenElse(scale, hn::Div(z, largest), z);
}

// Tangent along one axis from the values at the vertex (c) and its neighbours (minus, plus),
// each neighbour used where `has_*` holds (core/surface.cc, axis_tangent).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE LaneTangent<D> AxisTangent(D d, const V centre[3], const V minus[3], const V plus[3],
                                      M has_minus, M has_plus) {
  V t[3];
  for (int c = 0; c < 3; ++c) {
    const V from = hn::IfThenElse(has_minus, minus[c], centre[c]);
    const V to = hn::IfThenElse(has_plus, plus[c], centre[c]);
    t[c] = hn::Sub(to, from);
  }
  ScaleToUnitMax(d, t[0], t[1], t[2]);
  return {t[0], t[1], t[2], hn::Or(has_minus, has_plus)};
}

// to - from as it is and scaled (core/surface.cc, side_difference).
template <class D>
struct LaneSideDifference {
  LaneTangent<D> raw, scaled;
};

template <class D, class V = hn::Vec<D>>
HWY_INLINE LaneSideDifference<D> SideDifference(D d, const V from[3], const V to[3]) {
  LaneSideDifference<D> s;
  s.raw = {hn::Sub(to[0], from[0]), hn::Sub(to[1], from[1]), hn::Sub(to[2], from[2]),
           hn::FirstN(d, 0)};
  s.scaled = s.raw;
  ScaleToUnitMax(d, s.scaled.x, s.scaled.h, s.scaled.z);
  return s;
}

// core/surface.cc, facing_weight: u along i, w along j; ray scaled, with its length.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V FacingWeight(D d, const LaneTangent<D>& u, const LaneTangent<D>& w, const V ray[3],
                          V ray_length, V inv_facing, V least) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V nx = hn::Neg(hn::Sub(hn::Mul(u.h, w.z), hn::Mul(u.z, w.h)));
  const V ny = hn::Sub(hn::Mul(u.x, w.z), hn::Mul(u.z, w.x));
  const V nz = hn::Neg(hn::Sub(hn::Mul(u.x, w.h), hn::Mul(u.h, w.x)));
  const V sign = hn::IfThenElse(hn::Gt(ny, zero), one, hn::Set(d, -1.0f));
  const V dot = hn::Add(hn::Add(hn::Mul(nx, ray[0]), hn::Mul(ny, ray[1])), hn::Mul(nz, ray[2]));
  const V facing = hn::Mul(hn::Neg(dot), sign);
  const V n_sq = hn::Add(hn::Add(hn::Mul(nx, nx), hn::Mul(ny, ny)), hn::Mul(nz, nz));
  const V length = hn::Mul(hn::Sqrt(n_sq), ray_length);
  const auto defined = hn::Gt(length, zero);
  // Lanes without a cosine divide by 1 instead and are replaced by 1 below.
  const V weight = hn::Mul(hn::Div(facing, hn::IfThenElse(defined, length, one)), inv_facing);
  const V clamped = hn::IfThenElse(hn::Lt(weight, least), least,
                                   hn::IfThenElse(hn::Gt(weight, one), one, weight));
  return hn::IfThenElse(defined, clamped, one);
}

// core/surface.cc, weigh_sides, where `central` holds.
template <class D, class M = hn::Mask<D>, class V = hn::Vec<D>>
HWY_INLINE void WeighSides(D d, M central, LaneTangent<D>& t, const LaneSideDifference<D>& minus,
                           V w_minus, const LaneSideDifference<D>& plus, V w_plus) {
  const V one = hn::Set(d, 1.0f);
  const M unchanged = hn::And(hn::Eq(w_minus, one), hn::Eq(w_plus, one));
  const M change = hn::AndNot(unchanged, central);
  if (hn::AllFalse(d, change)) {
    return;
  }
  V x = hn::Add(hn::Mul(w_minus, minus.raw.x), hn::Mul(w_plus, plus.raw.x));
  V h = hn::Add(hn::Mul(w_minus, minus.raw.h), hn::Mul(w_plus, plus.raw.h));
  V z = hn::Add(hn::Mul(w_minus, minus.raw.z), hn::Mul(w_plus, plus.raw.z));
  ScaleToUnitMax(d, x, h, z);
  t.x = hn::IfThenElse(change, x, t.x);
  t.h = hn::IfThenElse(change, h, t.h);
  t.z = hn::IfThenElse(change, z, t.z);
}

// The visible sides of one axis (core/surface.cc): `t` reweighted from the points before and
// after the vertex, where `central` holds. `other` is the other axis's central tangent; the
// patch of a side is (side, other) along i and (other, side) along j.
template <class D, class M = hn::Mask<D>, class V = hn::Vec<D>>
HWY_INLINE void WeighAxis(D d, M central, bool along_i, LaneTangent<D>& t, const V before[3],
                          const V centre[3], const V after[3], const LaneTangent<D>& other,
                          const V ray[3], V ray_length, V inv_facing, V least) {
  if (hn::AllFalse(d, central)) {
    return;
  }
  const auto minus = SideDifference(d, before, centre);
  const auto plus = SideDifference(d, centre, after);
  const auto weight = [&](const LaneTangent<D>& side) {
    return along_i ? FacingWeight(d, side, other, ray, ray_length, inv_facing, least)
                   : FacingWeight(d, other, side, ray, ray_length, inv_facing, least);
  };
  WeighSides(d, central, t, minus, weight(minus.scaled), plus, weight(plus.scaled));
}

void SurfaceRows(const SurfaceParams<float>& p, RowRange rows, SurfaceInputs<float> in,
                 SurfaceSpans<float> out) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  using M = hn::Mask<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const std::size_t size = in.valid.size();
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  // Values at k + offset for lanes l = 0 .. lanes - 1, reading only inside the buffers (lanes
  // outside read 0 and are masked by their validity, which is 0 there too).
  const auto load = [&](const auto* base, std::ptrdiff_t k, auto tag) {
    using T = std::remove_const_t<std::remove_pointer_t<decltype(base)>>;
    if (k >= 0 && std::size_t(k) + std::size_t(lanes) <= size) {
      return hn::LoadU(tag, base + k);
    }
    HWY_ALIGN T local[HWY_MAX_BYTES / sizeof(float)] = {};
    for (int l = 0; l < lanes; ++l) {
      const std::ptrdiff_t at = k + l;
      local[l] = at >= 0 && std::size_t(at) < size ? base[at] : T(0);
    }
    return hn::Load(tag, local);
  };
  const auto valid_at = [&](std::ptrdiff_t k) {
    return hn::RebindMask(d, hn::Ne(hn::PromoteTo(di, load(in.valid.data(), k, d8)), hn::Zero(di)));
  };
  const auto values_at = [&](std::ptrdiff_t k, V v[3]) {
    v[0] = load(in.dx.data(), k, d);
    v[1] = load(in.height.data(), k, d);
    v[2] = load(in.dz.data(), k, d);
  };
  const V min_sine_sq = hn::Set(d, p.min_sine_sq);
  const V max_slope = hn::Set(d, p.max_slope);
  const V water_level = hn::Set(d, p.water_level);
  const V inv_facing = hn::Set(d, p.inv_silhouette_facing);
  const V least = hn::Set(d, p.hidden_side_weight);
  const auto draw_bit = hn::Set(di, kDraw);
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < p.pitch; i += lanes) {
      const std::ptrdiff_t k = std::ptrdiff_t(j) * p.pitch + i;
      const auto column = hn::Iota(di, i);
      const M inside = hn::RebindMask(d, hn::Lt(column, hn::Set(di, p.width)));
      M active = hn::And(inside, valid_at(k));
      if (!in.need.empty()) {
        const auto bits = hn::PromoteTo(di, load(in.need.data(), k, d8));
        active = hn::And(active, hn::RebindMask(d, hn::Ne(hn::And(bits, draw_bit), hn::Zero(di))));
      }
      V nx_out = zero, ny_out = one, nz_out = zero, slope_out = zero, water_out = zero;
      if (!hn::AllFalse(d, active)) {
        V centre[3], left[3], right[3], below[3], above[3];
        values_at(k, centre);
        values_at(k - 1, left);
        values_at(k + 1, right);
        const M has_left =
            hn::And(hn::RebindMask(d, hn::Gt(column, hn::Zero(di))), valid_at(k - 1));
        const M has_right = hn::And(
            hn::RebindMask(d, hn::Lt(hn::Add(column, hn::Set(di, 1)), hn::Set(di, p.width))),
            valid_at(k + 1));
        M has_below = hn::FirstN(d, 0), has_above = hn::FirstN(d, 0);
        if (j > 0) {
          values_at(k - p.pitch, below);
          has_below = hn::And(inside, valid_at(k - p.pitch));
        } else {
          values_at(k, below);
        }
        if (j + 1 < p.height) {
          values_at(k + p.pitch, above);
          has_above = hn::And(inside, valid_at(k + p.pitch));
        } else {
          values_at(k, above);
        }
        auto a = AxisTangent(d, centre, left, right, has_left, has_right);
        auto b = AxisTangent(d, centre, below, above, has_below, has_above);
        {  // Visible sides (core/surface.cc): weights from the central tangents.
          V ray[3] = {centre[0], centre[1], centre[2]};
          ScaleToUnitMax(d, ray[0], ray[1], ray[2]);
          const V ray_length = hn::Sqrt(hn::Add(
              hn::Add(hn::Mul(ray[0], ray[0]), hn::Mul(ray[1], ray[1])), hn::Mul(ray[2], ray[2])));
          const M seen = hn::Gt(ray_length, zero);
          const M a_central = hn::And(seen, hn::And(has_left, has_right));
          const M b_central = hn::And(seen, hn::And(has_below, has_above));
          auto weighted_a = a, weighted_b = b;
          WeighAxis(d, a_central, true, weighted_a, left, centre, right, b, ray, ray_length,
                    inv_facing, least);
          WeighAxis(d, b_central, false, weighted_b, below, centre, above, a, ray, ray_length,
                    inv_facing, least);
          a = weighted_a;
          b = weighted_b;
        }
        const V a_sq = hn::Add(hn::Mul(a.x, a.x), hn::Mul(a.z, a.z));
        const V b_sq = hn::Add(hn::Mul(b.x, b.x), hn::Mul(b.z, b.z));
        const V det = hn::Sub(hn::Mul(a.x, b.z), hn::Mul(a.z, b.x));
        const M both =
            hn::And(hn::And(a.present, b.present),
                    hn::Gt(hn::Mul(det, det), hn::Mul(hn::Mul(min_sine_sq, a_sq), b_sq)));
        const V sign = hn::IfThenElse(hn::Gt(det, zero), one, hn::Set(d, -1.0f));
        const M only_a = hn::AndNot(both, hn::And(a.present, hn::Gt(a_sq, zero)));
        const M only_b = hn::AndNot(hn::Or(both, only_a), hn::And(b.present, hn::Gt(b_sq, zero)));
        V nx = zero, ny = one, nz = zero;
        nx = hn::IfThenElse(only_b, hn::Mul(hn::Neg(b.h), b.x), nx);
        ny = hn::IfThenElse(only_b, b_sq, ny);
        nz = hn::IfThenElse(only_b, hn::Mul(hn::Neg(b.h), b.z), nz);
        nx = hn::IfThenElse(only_a, hn::Mul(hn::Neg(a.h), a.x), nx);
        ny = hn::IfThenElse(only_a, a_sq, ny);
        nz = hn::IfThenElse(only_a, hn::Mul(hn::Neg(a.h), a.z), nz);
        nx = hn::IfThenElse(
            both, hn::Mul(hn::Neg(hn::Sub(hn::Mul(a.h, b.z), hn::Mul(a.z, b.h))), sign), nx);
        ny = hn::IfThenElse(both, hn::Mul(det, sign), ny);
        nz = hn::IfThenElse(
            both, hn::Mul(hn::Neg(hn::Sub(hn::Mul(a.x, b.h), hn::Mul(a.h, b.x))), sign), nz);
        const V largest = hn::Max(hn::Max(hn::Abs(nx), ny), hn::Abs(nz));
        nx = hn::Div(nx, largest);
        ny = hn::Div(ny, largest);
        nz = hn::Div(nz, largest);
        const V horizontal_sq = hn::Add(hn::Mul(nx, nx), hn::Mul(nz, nz));
        const V inv_length = hn::Div(one, hn::Sqrt(hn::Add(horizontal_sq, hn::Mul(ny, ny))));
        nx_out = hn::IfThenElse(active, hn::Mul(nx, inv_length), nx_out);
        ny_out = hn::IfThenElse(active, hn::Mul(ny, inv_length), ny_out);
        nz_out = hn::IfThenElse(active, hn::Mul(nz, inv_length), nz_out);
        // std::min(s, max_slope): max_slope < s ? max_slope : s.
        const V slope = hn::Div(hn::Sqrt(horizontal_sq), ny);
        slope_out = hn::IfThenElse(
            active, hn::IfThenElse(hn::Lt(max_slope, slope), max_slope, slope), slope_out);
        if (p.water_enabled) {
          // std::max(0, depth): 0 < depth ? depth : 0 (a depth of -0 gives +0).
          const V depth = hn::Sub(water_level, centre[1]);
          water_out =
              hn::IfThenElse(active, hn::IfThenElse(hn::Lt(zero, depth), depth, zero), water_out);
        }
      }
      hn::StoreU(nx_out, d, out.nx.data() + k);
      hn::StoreU(ny_out, d, out.ny.data() + k);
      hn::StoreU(nz_out, d, out.nz.data() + k);
      hn::StoreU(slope_out, d, out.slope.data() + k);
      hn::StoreU(water_out, d, out.water_depth.data() + k);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
