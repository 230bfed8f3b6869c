// A minimal 3-vector for the per-pixel code of stage 8, templated on the precision like every
// stage; the operation order of each function is part of its definition.
#pragma once

#include <cmath>

namespace relief {

template <class Real>
struct Vec3 {
  Real x, y, z;

  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator*(Real k) const { return {x * k, y * k, z * k}; }
  Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }  // per channel
};

template <class Real>
Real dot(const Vec3<Real>& a, const Vec3<Real>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class Real>
Vec3<Real> mix(const Vec3<Real>& a, const Vec3<Real>& b, Real t) {
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
}

// v / |v|, or `fallback` where |v|^2 is not a positive finite number (the sqrt's domain).
template <class Real>
Vec3<Real> normalize_or(const Vec3<Real>& v, const Vec3<Real>& fallback) {
  const Real length_sq = dot(v, v);
  if (!(length_sq > Real(0)) || !std::isfinite(length_sq)) {
    return fallback;
  }
  return v * (Real(1) / std::sqrt(length_sq));
}

template <class Real>
Real clamp01(Real t) {
  return t < Real(0) ? Real(0) : (t > Real(1) ? Real(1) : t);
}

// The cubic Hermite step on [0, 1] of an already normalised t.
template <class Real>
Real smooth01(Real t) {
  t = clamp01(t);
  return t * t * (Real(3) - Real(2) * t);
}

}  // namespace relief
