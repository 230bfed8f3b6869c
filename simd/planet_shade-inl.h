// Per-target planet part of stage 8 (core/planet_shading.h) for float, one pixel per lane: the
// rotation into a point's local frame, with the scalar code's operations in its order (a
// planet frame's background is simd/background-inl.h's).
// Included by simd/shade-inl.h and simd/background-inl.h inside their per-target sections
// (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_PLANET_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PLANET_SHADE_INL_H_
#undef RELIEF_SIMD_PLANET_SHADE_INL_H_
#else
#define RELIEF_SIMD_PLANET_SHADE_INL_H_
#endif

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/planet_shading.h"
#include "core/stage_params.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// to_local_frame (planet_shading.h): v rotated by the rotation taking the unit `up` to
// (0, 1, 0); v itself where up.y <= -0.999. The products with w.y = 0 are kept, as the scalar
// code forms them (0 * x is not folded without fast-math: -0 and NaN).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> ToLocalFrame(D d, const V3<V>& v, const V3<V>& up) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto rotate = hn::Gt(up.y, hn::Set(d, -0.999f));
  const V3<V> w{hn::Neg(up.z), zero, up.x};
  const auto cross = [](const V3<V>& a, const V3<V>& b) {
    return V3<V>{hn::Sub(hn::Mul(a.y, b.z), hn::Mul(a.z, b.y)),
                 hn::Sub(hn::Mul(a.z, b.x), hn::Mul(a.x, b.z)),
                 hn::Sub(hn::Mul(a.x, b.y), hn::Mul(a.y, b.x))};
  };
  const V3<V> wv = cross(w, v);
  const V3<V> wwv = cross(w, wv);
  // Domain of the division: 1 + c >= 0.001 in the lanes that use it; the others divide by a
  // value they discard (1 where up.y is -1 or below: finite).
  const V k = hn::Div(one, hn::IfThenElse(rotate, hn::Add(one, up.y), one));
  const V3<V> rotated = Add3(Add3(v, wv), Scale3(wwv, k));
  return Select3(rotate, rotated, v);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
