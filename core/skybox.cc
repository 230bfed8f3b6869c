#include "core/skybox.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relief {

template <class Real>
CubeFaceCoordinate<Real> cube_face_coordinate(const Vec3<Real>& d) {
  const Real ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  CubeFaceCoordinate<Real> c;
  Real sc, tc, major;
  // Table 8.19: (sc, tc, ma) per face; negation is exact.
  if (ax >= ay && ax >= az) {
    c.face = d.x < Real(0) ? 1 : 0;
    sc = c.face == 0 ? -d.z : d.z;
    tc = -d.y;
    major = ax;
  } else if (ay >= az) {
    c.face = d.y < Real(0) ? 3 : 2;
    sc = d.x;
    tc = c.face == 2 ? d.z : -d.z;
    major = ay;
  } else {
    c.face = d.z < Real(0) ? 5 : 4;
    sc = c.face == 4 ? d.x : -d.x;
    tc = -d.y;
    major = az;
  }
  // The division's domain: 0 < major <= the largest finite value, |sc|, |tc| <= major (false
  // for a NaN anywhere); elsewhere (zero, NaN, infinity) the +x face's centre.
  const bool inside = major > Real(0) && major <= std::numeric_limits<Real>::max() &&
                      std::abs(sc) <= major && std::abs(tc) <= major;
  if (!inside) {
    c.face = 0;
    sc = Real(0);
    tc = Real(0);
    major = Real(1);
  }
  // |sc|, |tc| <= major, so each quotient lies in [-1, 1] (correctly rounded division is
  // monotone) and s, t in [0, 1].
  c.s = (sc / major + Real(1)) * Real(0.5);
  c.t = (tc / major + Real(1)) * Real(0.5);
  return c;
}

template <class Real>
Vec3<Real> skybox_radiance(const Skybox& box, const Vec3<Real>& d) {
  const CubeFaceCoordinate<Real> c = cube_face_coordinate(d);
  const Real n = Real(box.size);
  // s, t in [0, 1]: x, y in [-1/2, n - 1/2], their floors in [-1, n - 1], exactly integers.
  const Real x = c.s * n - Real(0.5), y = c.t * n - Real(0.5);
  const Real fx = std::floor(x), fy = std::floor(y);
  const Real a = x - fx, b = y - fy;
  const int last = box.size - 1;
  const int i0 = std::clamp(static_cast<int>(fx), 0, last);
  const int i1 = std::clamp(static_cast<int>(fx) + 1, 0, last);
  const int j0 = std::clamp(static_cast<int>(fy), 0, last);
  const int j1 = std::clamp(static_cast<int>(fy) + 1, 0, last);
  const float* p00 = box.texel(c.face, j0, i0);
  const float* p10 = box.texel(c.face, j0, i1);
  const float* p01 = box.texel(c.face, j1, i0);
  const float* p11 = box.texel(c.face, j1, i1);
  Real out[3];
  for (int k = 0; k < 3; ++k) {
    const Real bottom = Real(p00[k]) + a * (Real(p10[k]) - Real(p00[k]));
    const Real top = Real(p01[k]) + a * (Real(p11[k]) - Real(p01[k]));
    out[k] = bottom + b * (top - bottom);
  }
  return {out[0], out[1], out[2]};
}

template CubeFaceCoordinate<float> cube_face_coordinate<float>(const Vec3<float>&);
template CubeFaceCoordinate<double> cube_face_coordinate<double>(const Vec3<double>&);
template Vec3<float> skybox_radiance<float>(const Skybox&, const Vec3<float>&);
template Vec3<double> skybox_radiance<double>(const Skybox&, const Vec3<double>&);

}  // namespace relief
