// Per-target skybox lookup of core/skybox.cc for float, one direction per lane:
// cube_face_coordinate's face choice and (s, t) as masks and selects over the same operations,
// then the face's bilinear filter with edge clamping, its texels gathered per channel. Every
// lane's indices lie inside the faces (clamped to the face, the face in 0 ... 5), so no gather
// reads outside them whatever the lane holds.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_SKYBOX_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SKYBOX_INL_H_
#undef RELIEF_SIMD_SKYBOX_INL_H_
#else
#define RELIEF_SIMD_SKYBOX_INL_H_
#endif

#include <limits>

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/skybox.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

static_assert(18LL * limits::kMaxSkyboxSize * limits::kMaxSkyboxSize < (1LL << 31),
              "the faces' indices fit int32");

// A Skybox as the kernels read it; texels null without one.
struct SkyboxView {
  const float* texels = nullptr;
  int size = 0;
};

inline SkyboxView skybox_view_of(const Skybox* box) {
  SkyboxView v;
  if (box != nullptr && box->size > 0) {
    v.texels = box->texels.data();
    v.size = box->size;
  }
  return v;
}

// skybox_radiance (skybox.cc) of directions `dir`.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> SkyboxRadiance(D d, const SkyboxView& box, const V3<V>& dir) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V ax = hn::Abs(dir.x), ay = hn::Abs(dir.y), az = hn::Abs(dir.z);
  // cube_face_coordinate: x where it is the largest (ties to x), else y over z (ties to y).
  const auto is_x = hn::And(hn::Ge(ax, ay), hn::Ge(ax, az));
  const auto is_y = hn::AndNot(is_x, hn::Ge(ay, az));
  const auto neg_x = hn::Lt(dir.x, zero), neg_y = hn::Lt(dir.y, zero);
  const auto neg_z = hn::Lt(dir.z, zero);
  V sc = hn::IfThenElse(is_x, hn::IfThenElse(neg_x, dir.z, hn::Neg(dir.z)),
                        hn::IfThenElse(is_y, dir.x, hn::IfThenElse(neg_z, hn::Neg(dir.x), dir.x)));
  V tc = hn::IfThenElse(is_y, hn::IfThenElse(neg_y, hn::Neg(dir.z), dir.z), hn::Neg(dir.y));
  V major = hn::IfThenElse(is_x, ax, hn::IfThenElse(is_y, ay, az));
  const auto select_face = [&](auto mask, int negative, int positive) {
    return hn::IfThenElse(hn::RebindMask(di, mask), hn::Set(di, negative), hn::Set(di, positive));
  };
  VI face = hn::IfThenElse(
      hn::RebindMask(di, is_x), select_face(neg_x, 1, 0),
      hn::IfThenElse(hn::RebindMask(di, is_y), select_face(neg_y, 3, 2), select_face(neg_z, 5, 4)));
  // Outside the division's domain (zero, infinity, a NaN anywhere): the +x face's centre.
  const auto inside = hn::And(
      hn::And(hn::Gt(major, zero), hn::Le(major, hn::Set(d, std::numeric_limits<float>::max()))),
      hn::And(hn::Le(hn::Abs(sc), major), hn::Le(hn::Abs(tc), major)));
  const auto outside = hn::Not(inside);
  sc = hn::IfThenZeroElse(outside, sc);
  tc = hn::IfThenZeroElse(outside, tc);
  major = hn::IfThenElse(outside, one, major);
  face = hn::IfThenZeroElse(hn::RebindMask(di, outside), face);
  const V s = hn::Mul(hn::Add(hn::Div(sc, major), one), half);
  const V t = hn::Mul(hn::Add(hn::Div(tc, major), one), half);

  const V n = hn::Set(d, float(box.size));
  const V x = hn::Sub(hn::Mul(s, n), half), y = hn::Sub(hn::Mul(t, n), half);
  const V fx = hn::Floor(x), fy = hn::Floor(y);
  const V a = hn::Sub(x, fx), b = hn::Sub(y, fy);
  // fx, fy in [-1, n - 1]: whole numbers, converted exactly, then clamped to the face.
  const VI first = hn::Zero(di), last = hn::Set(di, box.size - 1), step = hn::Set(di, 1);
  const auto clamp = [&](VI v) { return hn::Min(hn::Max(v, first), last); };
  const VI x0 = hn::ConvertTo(di, fx), y0 = hn::ConvertTo(di, fy);
  const VI i0 = clamp(x0), i1 = clamp(hn::Add(x0, step));
  const VI j0 = clamp(y0), j1 = clamp(hn::Add(y0, step));
  // 3 ((face n + row) n + column): the texel's red (below 18 n^2 <= 2^31 - 1, static_assert
  // above), for any side n.
  const VI side = hn::Set(di, box.size);
  const auto times3 = [](VI v) { return hn::Add(hn::ShiftLeft<1>(v), v); };
  const VI row0 = hn::Mul(hn::Add(hn::Mul(face, side), j0), side);
  const VI row1 = hn::Mul(hn::Add(hn::Mul(face, side), j1), side);
  const VI k00 = times3(hn::Add(row0, i0)), k10 = times3(hn::Add(row0, i1));
  const VI k01 = times3(hn::Add(row1, i0)), k11 = times3(hn::Add(row1, i1));
  V out[3];
  for (int c = 0; c < 3; ++c) {
    const float* base = box.texels + c;
    const V p00 = hn::GatherIndex(d, base, k00), p10 = hn::GatherIndex(d, base, k10);
    const V p01 = hn::GatherIndex(d, base, k01), p11 = hn::GatherIndex(d, base, k11);
    const V bottom = hn::Add(p00, hn::Mul(a, hn::Sub(p10, p00)));
    const V top = hn::Add(p01, hn::Mul(a, hn::Sub(p11, p01)));
    out[c] = hn::Add(bottom, hn::Mul(b, hn::Sub(top, bottom)));
  }
  return {out[0], out[1], out[2]};
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
