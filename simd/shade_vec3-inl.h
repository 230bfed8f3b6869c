// Per-target building blocks of stage 8's kernel: core/vec3.h on vectors of pixels, one lane
// per pixel, each function with the scalar code's operations in its order (dot is
// (x x' + y y') + z z'; mix is a + t (b - a); normalize_or multiplies by 1 / sqrt). Only
// operations every target rounds alike: no FMA, no approximations, and no hn::Min/Max or hn::Ne
// on floats (their NaN behaviour differs between targets): the std::min/max/clamp of the scalar
// code become ordered compares and IfThenElse, which give the scalar result for every input.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_SHADE_VEC3_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SHADE_VEC3_INL_H_
#undef RELIEF_SIMD_SHADE_VEC3_INL_H_
#else
#define RELIEF_SIMD_SHADE_VEC3_INL_H_
#endif

#include <hwy/highway.h>

#include "core/vec3.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Vec3 with one pixel per lane.
template <class V>
struct V3 {
  V x, y, z;
};

template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> Set3(D d, const Vec3<float>& v) {
  return {hn::Set(d, v.x), hn::Set(d, v.y), hn::Set(d, v.z)};
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> Set3(D d, float x, float y, float z) {
  return {hn::Set(d, x), hn::Set(d, y), hn::Set(d, z)};
}

template <class V>
HWY_INLINE V3<V> Add3(const V3<V>& a, const V3<V>& b) {
  return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)};
}

template <class V>
HWY_INLINE V3<V> Sub3(const V3<V>& a, const V3<V>& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}

// Vec3 * k.
template <class V>
HWY_INLINE V3<V> Scale3(const V3<V>& a, V k) {
  return {hn::Mul(a.x, k), hn::Mul(a.y, k), hn::Mul(a.z, k)};
}

// Vec3 * Vec3, per channel.
template <class V>
HWY_INLINE V3<V> Mul3(const V3<V>& a, const V3<V>& b) {
  return {hn::Mul(a.x, b.x), hn::Mul(a.y, b.y), hn::Mul(a.z, b.z)};
}

// dot (vec3.h): (a.x b.x + a.y b.y) + a.z b.z.
template <class V>
HWY_INLINE V Dot3(const V3<V>& a, const V3<V>& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}

// mix (vec3.h): a + t (b - a), one channel.
template <class V>
HWY_INLINE V Mix(V a, V b, V t) {
  return hn::Add(a, hn::Mul(t, hn::Sub(b, a)));
}

// mix (vec3.h): a + t (b - a) per channel.
template <class V>
HWY_INLINE V3<V> Mix3(const V3<V>& a, const V3<V>& b, V t) {
  return {Mix(a.x, b.x, t), Mix(a.y, b.y, t), Mix(a.z, b.z, t)};
}

template <class M, class V>
HWY_INLINE V3<V> Select3(M m, const V3<V>& yes, const V3<V>& no) {
  return {hn::IfThenElse(m, yes.x, no.x), hn::IfThenElse(m, yes.y, no.y),
          hn::IfThenElse(m, yes.z, no.z)};
}

// normalize_or (vec3.h) given length_sq = dot(v, v): v * (1 / sqrt(length_sq)), or the
// fallback where length_sq is not a positive finite number. The other lanes' sqrt of a negative
// or NaN value is discarded.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> NormalizeOrWith(D d, const V3<V>& v, V length_sq, const V3<V>& fallback) {
  const auto ok = hn::And(hn::Gt(length_sq, hn::Zero(d)), hn::IsFinite(length_sq));
  const V inv = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(length_sq));
  return Select3(ok, Scale3(v, inv), fallback);
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> NormalizeOr(D d, const V3<V>& v, const V3<V>& fallback) {
  return NormalizeOrWith(d, v, Dot3(v, v), fallback);
}

// clamp01 (vec3.h): t < 0 ? 0 : (t > 1 ? 1 : t); NaN passes through, -0 stays -0.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Clamp01(D d, V t) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  return hn::IfThenElse(hn::Lt(t, zero), zero, hn::IfThenElse(hn::Gt(t, one), one, t));
}

// smooth01 (vec3.h): t t (3 - 2 t) of the clamped t.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Smooth01(D d, V t) {
  t = Clamp01(d, t);
  return hn::Mul(hn::Mul(t, t), hn::Sub(hn::Set(d, 3.0f), hn::Mul(hn::Set(d, 2.0f), t)));
}

// std::max(a, b) = a < b ? b : a, and std::min(a, b) = b < a ? b : a, for any NaN.
template <class V>
HWY_INLINE V StdMax(V a, V b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

template <class V>
HWY_INLINE V StdMin(V a, V b) {
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
