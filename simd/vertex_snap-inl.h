// Per-target body of simd/vertex_snap.h: raster/vertex_prepare.cc's two passes, the same
// float operations in the same order. Rounding to the 16.8 grid is done in float, exactly:
// adding and removing 2^23 to |s| < 2^23 leaves its nearest integer, ties to even, which is
// the double rounding of the scalar path (the value is a float either way); Highway's own
// NearestInt is not used because its emulated targets round s + 0.5 in float first.
#if defined(RELIEF_SIMD_VERTEX_SNAP_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_VERTEX_SNAP_INL_H_
#undef RELIEF_SIMD_VERTEX_SNAP_INL_H_
#else
#define RELIEF_SIMD_VERTEX_SNAP_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <limits>

#include <hwy/highway.h>

#include "simd/vertex_snap.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

#undef RELIEF_SNAP_LANES
#define RELIEF_SNAP_LANES (HWY_MAX_BYTES / sizeof(float))

// Runs body(offset, count, staged) over [0, n): whole vectors in place, the tail through
// staging buffers the body fills and empties itself (staged = true).
template <class Body>
HWY_INLINE void for_each_vector(std::size_t n, std::size_t lanes, const Body& body) {
  std::size_t e = 0;
  for (; e + lanes <= n; e += lanes) {
    body(e, lanes, false);
  }
  if (e < n) {
    body(e, n - e, true);
  }
}

// ordinary_clip_coordinate as a mask: the magnitude is 0 or that of a normal float.
template <class DI, class VI>
HWY_INLINE auto ordinary(DI di, VI magnitude) {
  return hn::Or(hn::Eq(magnitude, hn::Zero(di)),
                hn::And(hn::Gt(magnitude, hn::Set(di, 0x007fffff)),
                        hn::Lt(magnitude, hn::Set(di, 0x7f800000))));
}

void WindowVertices(const SnapConstants& c, const float* HWY_RESTRICT vx,
                    const float* HWY_RESTRICT vy, const float* HWY_RESTRICT vz,
                    const float* HWY_RESTRICT vw, const std::uint8_t* HWY_RESTRICT valid,
                    const std::uint8_t* HWY_RESTRICT need, std::size_t n,
                    float* HWY_RESTRICT window_x, float* HWY_RESTRICT window_y,
                    float* HWY_RESTRICT window_z, std::uint32_t* HWY_RESTRICT bits) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using namespace snap_bits;
  const auto magnitude_bits = hn::Set(di, 0x7fffffff);
  const auto gx = hn::Set(d, c.guard_x), gy = hn::Set(d, c.guard_y);
  const auto sx = hn::Set(d, c.scale_x), sy = hn::Set(d, c.scale_y);
  const auto tx = hn::Set(d, c.translate_x), ty = hn::Set(d, c.translate_y);
  const auto min_normal = hn::Set(d, std::numeric_limits<float>::min());
  const auto max_float = hn::Set(d, std::numeric_limits<float>::max());
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const auto zero_i = hn::Zero(di);
  const auto bit = [&](auto mask, std::uint32_t value) {
    return hn::IfThenElseZero(mask, hn::Set(di, static_cast<std::int32_t>(value)));
  };
  for_each_vector(n, hn::Lanes(d), [&](std::size_t e, std::size_t count, bool staged) {
    HWY_ALIGN float in[4][RELIEF_SNAP_LANES] = {};
    HWY_ALIGN std::uint8_t in8[2][RELIEF_SNAP_LANES] = {};
    const float* p[4] = {vx + e, vy + e, vz + e, vw + e};
    const std::uint8_t* valid_at = valid != nullptr ? valid + e : nullptr;
    const std::uint8_t* need_at = need != nullptr ? need + e : nullptr;
    if (staged) {
      for (int k = 0; k < 4; ++k) {
        for (std::size_t l = 0; l < count; ++l) {
          in[k][l] = p[k][l];
        }
        p[k] = in[k];
      }
      for (std::size_t l = 0; l < count; ++l) {
        in8[0][l] = valid_at != nullptr ? valid_at[l] : 0;
        in8[1][l] = need_at != nullptr ? need_at[l] : 0;
      }
      valid_at = valid_at != nullptr ? in8[0] : nullptr;
      need_at = need_at != nullptr ? in8[1] : nullptr;
    }
    const auto x = hn::LoadU(d, p[0]), y = hn::LoadU(d, p[1]);
    const auto z = hn::LoadU(d, p[2]), w = hn::LoadU(d, p[3]);
    auto is_valid = hn::Eq(zero_i, zero_i);
    if (valid_at != nullptr) {
      is_valid = hn::Ne(hn::PromoteTo(di, hn::LoadU(d8, valid_at)), zero_i);
    }
    auto is_drawn = is_valid;
    if (need_at != nullptr) {
      const auto need_bits = hn::PromoteTo(di, hn::LoadU(d8, need_at));
      is_drawn = hn::And(is_drawn, hn::Ne(hn::And(need_bits, hn::Set(di, 2)), zero_i));
    }
    // plain_clip_vertex: four ordinary coordinates, not all zero.
    const auto mx = hn::And(hn::BitCast(di, x), magnitude_bits);
    const auto my = hn::And(hn::BitCast(di, y), magnitude_bits);
    const auto mz = hn::And(hn::BitCast(di, z), magnitude_bits);
    const auto mw = hn::And(hn::BitCast(di, w), magnitude_bits);
    const auto plain = hn::And(hn::And(hn::And(ordinary(di, mx), ordinary(di, my)),
                                       hn::And(ordinary(di, mz), ordinary(di, mw))),
                               hn::Ne(hn::Or(hn::Or(mx, my), hn::Or(mz, mw)), zero_i));
    // The near and far bits, !(w >= z) and !(z >= 0) (NaN sets them, as in the loop).
    const auto near_bit = hn::RebindMask(di, hn::Not(hn::Ge(w, z)));
    const auto far_bit = hn::RebindMask(di, hn::Not(hn::Ge(z, zero)));
    // The guard bits where float decides them (raster/vertex_prepare.cc says why it can).
    const auto gxw = hn::Mul(gx, w), gyw = hn::Mul(gy, w);
    const auto guards_inside = hn::RebindMask(
        di,
        hn::And(hn::And(hn::And(hn::Gt(w, zero), hn::Ge(gxw, min_normal)),
                        hn::And(hn::Le(gxw, max_float), hn::Ge(gyw, min_normal))),
                hn::And(hn::Le(gyw, max_float), hn::And(hn::Le(hn::Mul(hn::Abs(x), two), gxw),
                                                        hn::Le(hn::Mul(hn::Abs(y), two), gyw)))));
    const auto inv_w = hn::Div(one, w);
    const auto wx = hn::Add(hn::Mul(hn::Mul(x, inv_w), sx), tx);
    const auto wy = hn::Add(hn::Mul(hn::Mul(y, inv_w), sy), ty);
    const auto wz = hn::Mul(z, inv_w);
    const auto b =
        hn::Or(hn::Or(hn::Or(bit(is_valid, kValid), bit(is_drawn, kDrawn)), bit(plain, kPlain)),
               hn::Or(hn::Or(bit(near_bit, 1u << kOutcodeShift), bit(far_bit, 2u << kOutcodeShift)),
                      bit(hn::Not(guards_inside), kGuardUndecided)));
    if (!staged) {
      hn::StoreU(wx, d, window_x + e);
      hn::StoreU(wy, d, window_y + e);
      hn::StoreU(wz, d, window_z + e);
      hn::StoreU(hn::BitCast(hn::RebindToUnsigned<decltype(d)>(), b),
                 hn::RebindToUnsigned<decltype(d)>(), bits + e);
      return;
    }
    HWY_ALIGN float out[3][RELIEF_SNAP_LANES];
    HWY_ALIGN std::int32_t out_bits[RELIEF_SNAP_LANES];
    hn::Store(wx, d, out[0]);
    hn::Store(wy, d, out[1]);
    hn::Store(wz, d, out[2]);
    hn::Store(b, di, out_bits);
    for (std::size_t l = 0; l < count; ++l) {
      window_x[e + l] = out[0][l];
      window_y[e + l] = out[1][l];
      window_z[e + l] = out[2][l];
      bits[e + l] = static_cast<std::uint32_t>(out_bits[l]);
    }
  });
}

// std::floor of |x| < 2^31 as raster's floor_small computes it: truncated through int32,
// given x's sign, then one less where truncation went up.
template <class D, class V>
HWY_INLINE V FloorSmall(D d, V x) {
  const hn::RebindToSigned<D> di;
  const V truncated = hn::ConvertTo(d, hn::ConvertTo(di, x));
  const V t = hn::Or(truncated, hn::And(x, hn::Set(d, -0.0f)));
  return hn::Sub(t, hn::IfThenElseZero(hn::Gt(t, x), hn::Set(d, 1.0f)));
}

// snap_to_fixed: round half to even of (x - 0.5) * 256, |x| <= 2^21 + 1 (or 0).
template <class D, class V>
HWY_INLINE auto SnapToFixed(D d, V x) {
  const hn::RebindToSigned<D> di;
  const V scaled = hn::Mul(hn::Sub(x, hn::Set(d, 0.5f)), hn::Set(d, 256.0f));
  const V magnitude = hn::Abs(scaled);
  const V two23 = hn::Set(d, 8388608.0f);
  const V rounded = hn::Sub(hn::Add(magnitude, two23), two23);  // exact for |s| < 2^23
  const V nearest = hn::IfThenElse(hn::Lt(magnitude, two23), hn::CopySign(rounded, scaled), scaled);
  return hn::ConvertTo(di, nearest);
}

void SnapVertices(std::size_t n, const std::uint32_t* HWY_RESTRICT bits,
                  const float* HWY_RESTRICT window_x, const float* HWY_RESTRICT window_y,
                  std::uint8_t* HWY_RESTRICT flags, std::uint8_t* HWY_RESTRICT outcode,
                  float* HWY_RESTRICT floor_x, float* HWY_RESTRICT floor_y,
                  std::int32_t* HWY_RESTRICT fx, std::int32_t* HWY_RESTRICT fy) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using namespace snap_bits;
  // kSnapLimitPixels (raster/setup_internal.h): 2^21 + 1, exact in float.
  const auto limit = hn::Set(d, 2097153.0f);
  const auto zero_i = hn::Zero(di);
  for_each_vector(n, hn::Lanes(d), [&](std::size_t e, std::size_t count, bool staged) {
    HWY_ALIGN float in[2][RELIEF_SNAP_LANES] = {};
    HWY_ALIGN std::int32_t in_bits[RELIEF_SNAP_LANES] = {};
    const float* px = window_x + e;
    const float* py = window_y + e;
    const std::int32_t* pb = reinterpret_cast<const std::int32_t*>(bits + e);
    if (staged) {
      for (std::size_t l = 0; l < count; ++l) {
        in[0][l] = px[l];
        in[1][l] = py[l];
        in_bits[l] = pb[l];
      }
      px = in[0], py = in[1], pb = in_bits;
    }
    const auto x = hn::LoadU(d, px), y = hn::LoadU(d, py);
    const auto b = hn::LoadU(di, pb);
    const auto code = hn::And(hn::ShiftRight<kOutcodeShift>(b), hn::Set(di, kOutcodeMask));
    const auto snapped =
        hn::And(hn::And(hn::Ne(hn::And(b, hn::Set(di, kPlain)), zero_i), hn::Eq(code, zero_i)),
                hn::RebindMask(di, hn::And(hn::Lt(hn::Abs(x), limit), hn::Lt(hn::Abs(y), limit))));
    const auto keep = hn::RebindMask(d, snapped);
    const auto sx = hn::IfThenElseZero(keep, x), sy = hn::IfThenElseZero(keep, y);
    const auto f = hn::Or(hn::And(b, hn::Set(di, kValid | kDrawn | kPlain)),
                          hn::IfThenElseZero(snapped, hn::Set(di, kSnapped)));
    const auto floors_x = FloorSmall(d, sx), floors_y = FloorSmall(d, sy);
    const auto fixed_x = SnapToFixed(d, sx), fixed_y = SnapToFixed(d, sy);
    const auto flags8 = hn::DemoteTo(d8, f), code8 = hn::DemoteTo(d8, code);
    if (!staged) {
      hn::StoreU(floors_x, d, floor_x + e);
      hn::StoreU(floors_y, d, floor_y + e);
      hn::StoreU(fixed_x, di, fx + e);
      hn::StoreU(fixed_y, di, fy + e);
      hn::StoreU(flags8, d8, flags + e);
      hn::StoreU(code8, d8, outcode + e);
      return;
    }
    HWY_ALIGN float out_floor[2][RELIEF_SNAP_LANES];
    HWY_ALIGN std::int32_t out_fixed[2][RELIEF_SNAP_LANES];
    HWY_ALIGN std::uint8_t out8[2][RELIEF_SNAP_LANES];
    hn::Store(floors_x, d, out_floor[0]);
    hn::Store(floors_y, d, out_floor[1]);
    hn::Store(fixed_x, di, out_fixed[0]);
    hn::Store(fixed_y, di, out_fixed[1]);
    hn::Store(flags8, d8, out8[0]);
    hn::Store(code8, d8, out8[1]);
    for (std::size_t l = 0; l < count; ++l) {
      floor_x[e + l] = out_floor[0][l];
      floor_y[e + l] = out_floor[1][l];
      fx[e + l] = out_fixed[0][l];
      fy[e + l] = out_fixed[1][l];
      flags[e + l] = out8[0][l];
      outcode[e + l] = out8[1][l];
    }
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
