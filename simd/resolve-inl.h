// Per-target body of simd/resolve.h: raster::PerspectivePlane::barycentrics, quad_weights and
// QuadWeights::at per lane, each lane a pixel of a row, its triangle's coefficients and vertex
// values gathered by its slot.
#if defined(RELIEF_SIMD_RESOLVE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_RESOLVE_INL_H_
#undef RELIEF_SIMD_RESOLVE_INL_H_
#else
#define RELIEF_SIMD_RESOLVE_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "simd/lane_loads-inl.h"
#include "simd/resolve.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

template <class D>
struct LaneTriangle {
  hn::Vec<D> k[3], ku[3], kv[3];
};

// raster::PerspectivePlane::barycentrics at (u, v): false lanes where undefined.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE M Barycentrics(D d, const LaneTriangle<D>& t, V u, V v, V b[3]) {
  V l[3];
  for (int i = 0; i < 3; ++i) {
    l[i] = hn::Add(hn::Add(t.k[i], hn::Mul(t.ku[i], u)), hn::Mul(t.kv[i], v));
  }
  const V sum = hn::Add(hn::Add(l[0], l[1]), l[2]);
  const V huge = hn::Set(d, 1.7976931348623157e308);
  // |sum| > 0 and finite: 0 < |sum| <= DBL_MAX (NaN fails both compares).
  const V magnitude = hn::Abs(sum);
  M ok = hn::And(hn::Gt(magnitude, hn::Zero(d)), hn::Le(magnitude, huge));
  const V inv_sum = hn::Div(hn::Set(d, 1.0), sum);
  for (int i = 0; i < 3; ++i) {
    b[i] = hn::Mul(l[i], inv_sum);
    ok = hn::And(ok, hn::Le(hn::Abs(b[i]), huge));
  }
  return ok;
}

// QuadWeights::at: b0 a0 + b1 a1 + b2 a2, in double.
template <class V>
HWY_INLINE V At(const V b[3], const V a[3]) {
  return hn::Add(hn::Add(hn::Mul(b[0], a[0]), hn::Mul(b[1], a[1])), hn::Mul(b[2], a[2]));
}

void SetUpPlanes(const float* HWY_RESTRICT clip_x, const float* HWY_RESTRICT clip_y,
                 const float* HWY_RESTRICT clip_w, const WindowTransform& window,
                 const std::int32_t* const vertex[3], std::size_t count, double* const k[3],
                 double* const ku[3], double* const kv[3]) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const hn::Rebind<std::int32_t, decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V scale_x = hn::Set(d, window.scale_x), scale_y = hn::Set(d, window.scale_y);
  const V translate_x = hn::Set(d, window.translate_x);
  const V translate_y = hn::Set(d, window.translate_y);
  for (std::size_t s = 0; s < count; s += lanes) {
    // Past the last slot, lanes use slot 0's vertices and are not stored.
    HWY_ALIGN std::int32_t index[3][HWY_MAX_BYTES / sizeof(double)] = {};
    for (int c = 0; c < 3; ++c) {
      for (std::size_t l = 0; l < lanes; ++l) {
        index[c][l] = s + l < count ? vertex[c][s + l] : vertex[c][0];
      }
    }
    V x[3], y[3], w[3];
    for (int c = 0; c < 3; ++c) {
      const auto v = hn::Load(di, index[c]);
      // VertexPositions::get: X = x s_x + W t_x, Y = y s_y + W t_y, in double.
      w[c] = hn::PromoteTo(d, hn::GatherIndex(df, clip_w, v));
      x[c] = hn::Add(hn::Mul(hn::PromoteTo(d, hn::GatherIndex(df, clip_x, v)), scale_x),
                     hn::Mul(w[c], translate_x));
      y[c] = hn::Add(hn::Mul(hn::PromoteTo(d, hn::GatherIndex(df, clip_y, v)), scale_y),
                     hn::Mul(w[c], translate_y));
    }
    HWY_ALIGN double out[9][HWY_MAX_BYTES / sizeof(double)];
    for (int i = 0; i < 3; ++i) {
      const int a = (i + 1) % 3, b = (i + 2) % 3;
      hn::Store(hn::Sub(hn::Mul(x[a], y[b]), hn::Mul(y[a], x[b])), d, out[i]);
      hn::Store(hn::Sub(hn::Mul(y[a], w[b]), hn::Mul(w[a], y[b])), d, out[3 + i]);
      hn::Store(hn::Sub(hn::Mul(w[a], x[b]), hn::Mul(x[a], w[b])), d, out[6 + i]);
    }
    for (std::size_t l = 0; l < lanes && s + l < count; ++l) {
      for (int i = 0; i < 3; ++i) {
        k[i][s + l] = out[i][l];
        ku[i][s + l] = out[3 + i][l];
        kv[i][s + l] = out[6 + i][l];
      }
    }
  }
}

void ResolveRect(const ResolveSlots& slots, const ResolveStreams& streams,
                 const std::int32_t* HWY_RESTRICT slot, int x0, int y0, int width, int height,
                 int stride, const ResolveTargets& out) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const hn::Rebind<std::int32_t, decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const V half = hn::Set(d, 0.5);
  const V third = hn::Set(d, 1.0 / 3.0);
  for (int j = 0; j < height; ++j) {
    const int py = y0 + j;
    const V v_here = hn::Set(d, double(py) + 0.5);
    const V v_partner = hn::Set(d, double(py ^ 1) + 0.5);
    const V sign_y = hn::Set(d, (py & 1) ? -1.0 : 1.0);
    for (int i = 0; i < width; i += lanes) {
      const int count = width - i < lanes ? width - i : lanes;
      const std::size_t at = static_cast<std::size_t>(j) * stride + i;
      const auto in_rect = hn::FirstN(di, static_cast<std::size_t>(count));
      // Lanes past the rectangle read slot -1 (not covered).
      const auto slot_index = hn::IfThenElse(in_rect, hn::LoadU(di, slot + at), hn::Set(di, -1));
      const auto covered_i = hn::Gt(slot_index, hn::Set(di, -1));
      if (hn::AllFalse(di, covered_i)) {
        continue;
      }
      const auto index = hn::IfThenElseZero(covered_i, slot_index);
      const auto covered = hn::RebindMask(df, covered_i);
      const auto wide_index = hn::PromoteTo(hn::Rebind<std::int64_t, decltype(d)>(), index);
      LaneTriangle<hn::ScalableTag<double>> t;
      for (int c = 0; c < 3; ++c) {
        t.k[c] = hn::GatherIndex(d, slots.k[c], wide_index);
        t.ku[c] = hn::GatherIndex(d, slots.ku[c], wide_index);
        t.kv[c] = hn::GatherIndex(d, slots.kv[c], wide_index);
      }
      // The lanes' records: column 3 f + c is stream f at vertex c (the group of nu and
      // lambert only when one of them, or the drop, is resolved; the drop's last value in a
      // fifth group). 40 index = 32 index + 8 index: shifts, on every target.
      const auto record = hn::Add(hn::ShiftLeft<5>(index), hn::ShiftLeft<3>(index));
      static_assert(kSlotRecordFloats == 40);
      const int groups = streams.drop != nullptr                               ? 5
                         : streams.nu != nullptr || streams.lambert != nullptr ? 4
                                                                               : 3;
      hn::Vec<decltype(df)> column[kSlotRecordFloats];
#if RELIEF_LANE_LOADS
      HWY_ALIGN std::int32_t lane_record[HWY_MAX_BYTES / sizeof(double)];
      hn::Store(record, di, lane_record);
      for (int g = 0; g < groups; ++g) {
        hn::Vec<decltype(df)> group[8];
        LoadColumns8(slots.records + 8 * g, lane_record, group);
        for (int c = 0; c < 8; ++c) {
          column[8 * g + c] = group[c];
        }
      }
#else
      for (int c = 0; c < 8 * groups; ++c) {
        column[c] = hn::GatherIndex(df, slots.records + c, record);
      }
#endif
      // Pixel centres of the lanes, and their quad partners in x (px ^ 1).
      const auto px = hn::Iota(di, x0 + i);
      const V u_here = hn::Add(hn::PromoteTo(d, px), half);
      const V u_partner = hn::Add(hn::PromoteTo(d, hn::Xor(px, hn::Set(di, 1))), half);
      const auto odd = hn::Eq(hn::And(px, hn::Set(di, 1)), hn::Set(di, 1));
      const V sign_x = hn::PromoteTo(d, hn::IfThenElse(odd, hn::Set(di, -1), hn::Set(di, 1)));
      V b[3], bx[3], by[3];
      const auto defined = Barycentrics(d, t, u_here, v_here, b);
      for (int c = 0; c < 3; ++c) {
        b[c] = hn::IfThenElse(defined, b[c], third);
      }
      const auto has_x = Barycentrics(d, t, u_partner, v_here, bx);
      const auto has_y = Barycentrics(d, t, u_here, v_partner, by);
      const auto values = [&](int stream, V a[3]) {
        for (int c = 0; c < 3; ++c) {
          a[c] = hn::PromoteTo(d, column[3 * stream + c]);
        }
      };
      const auto store = [&](float* target, V value) {
        hn::BlendedStore(hn::DemoteTo(df, value), covered, df, target + at);
      };
      const auto with_derivatives = [&](int stream, float* value, float* ddx, float* ddy) {
        V a[3];
        values(stream, a);
        const V centre = At(b, a);
        store(value, centre);
        store(ddx, hn::IfThenElseZero(has_x, hn::Mul(sign_x, hn::Sub(At(bx, a), centre))));
        store(ddy, hn::IfThenElseZero(has_y, hn::Mul(sign_y, hn::Sub(At(by, a), centre))));
      };
      const auto plain = [&](int stream, float* value) {
        V a[3];
        values(stream, a);
        store(value, At(b, a));
      };
      with_derivatives(0, out.dx, out.dx_ddx, out.dx_ddy);
      with_derivatives(1, out.dz, out.dz_ddx, out.dz_ddy);
      with_derivatives(2, out.height, out.height_ddx, out.height_ddy);
      plain(3, out.nx);
      plain(4, out.ny);
      plain(5, out.nz);
      plain(6, out.slope);
      if (streams.water_depth != nullptr) {
        plain(7, out.water_depth);
      } else {
        store(out.water_depth, hn::Zero(d));
      }
      if (streams.nu != nullptr) {
        plain(8, out.nu);
      }
      if (streams.lambert != nullptr) {
        plain(9, out.lambert);
      }
      if (streams.drop != nullptr) {
        plain(10, out.drop);
      }
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
