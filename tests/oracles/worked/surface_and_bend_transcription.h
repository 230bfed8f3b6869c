// Stage 4's normal and the planet's bend re-implemented from the text of the docs, not from the
// code: docs/architecture.md, "Stage 4, operation by operation" (the branch of a vertex with
// four valid neighbours, each side facing the eye by at least 1/4 so that "Visible sides"
// leaves both tangents central), and docs/planet.md, "The bend and the normals'
// rotation, operation by operation" (bend_vertices of a valid vertex, bend_normals off the
// nadir). tests/oracles/worked/worked_numbers.cc traces them to print those sections' worked
// numbers and compares them bit for bit with relief::surface_pass, relief::bend_vertices and
// relief::bend_normals.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/oracles/worked/det_math_transcription.h"

namespace relief::test::worked {

template <class Real>
struct Tangent {
  Real x = 0, h = 0, z = 0;
};

// The normal and slope of the vertex at index c of a grid stored with row length w, from
// stage 3's dx, dz and h; its four neighbours must be valid. out = (nx, ny, nz, slope).
template <class Real>
void spec_normal(const Real* dx, const Real* dz, const Real* h, int w, int c, Real out[4],
                 bool trace) {
  auto tangent = [&](int from, int to, const char* name) {
    Tangent<Real> t;
    t.x = dx[to] - dx[from];
    t.h = h[to] - h[from];
    t.z = dz[to] - dz[from];
    const Real largest = std::max({std::abs(t.x), std::abs(t.h), std::abs(t.z)});
    if (trace) {
      std::printf("  tangent %s: x h z = %.9g %.9g %.9g, largest %.9g\n", name, double(t.x),
                  double(t.h), double(t.z), double(largest));
    }
    if (largest > Real(0))
      t.x = t.x / largest, t.h = t.h / largest, t.z = t.z / largest;
    if (trace) {
      std::printf("     scaled:  %.9g %.9g %.9g\n", double(t.x), double(t.h), double(t.z));
    }
    return t;
  };
  const Tangent<Real> a = tangent(c - 1, c + 1, "a (i-1 -> i+1)");
  const Tangent<Real> b = tangent(c - w, c + w, "b (j-1 -> j+1)");
  const Real min_sine_sq = Real(1e-6 * 1e-6);  // kMinTangentSine squared
  const Real a_sq = a.x * a.x + a.z * a.z;
  const Real b_sq = b.x * b.x + b.z * b.z;
  const Real det = a.x * b.z - a.z * b.x;
  Real nx = 0, ny = 1, nz = 0;
  if (det * det > min_sine_sq * a_sq * b_sq) {
    const Real sign = det > Real(0) ? Real(1) : Real(-1);
    nx = -(a.h * b.z - a.z * b.h) * sign;
    ny = det * sign;
    nz = -(a.x * b.h - a.h * b.x) * sign;
  }
  if (trace) {
    std::printf("  a_sq %.9g  b_sq %.9g  det %.9g\n", double(a_sq), double(b_sq), double(det));
    std::printf("  unnormalised n: %.9g %.9g %.9g\n", double(nx), double(ny), double(nz));
  }
  const Real largest = std::max({std::abs(nx), ny, std::abs(nz)});
  nx = nx / largest;
  ny = ny / largest;
  nz = nz / largest;
  const Real horizontal_sq = nx * nx + nz * nz;
  const Real inv_length = Real(1) / std::sqrt(horizontal_sq + ny * ny);
  if (trace) {
    std::printf("  largest %.9g -> %.9g %.9g %.9g; horizontal_sq %.9g; inv_length %.9g\n",
                double(largest), double(nx), double(ny), double(nz), double(horizontal_sq),
                double(inv_length));
  }
  out[0] = nx * inv_length;
  out[1] = ny * inv_length;
  out[2] = nz * inv_length;
  out[3] = std::min(std::sqrt(horizontal_sq) / ny, Real(1e6));  // kMaxSlope
}

// bend_vertices of one valid vertex, every intermediate kept for the worked table.
template <class Real>
struct BentVertex {
  Real rho, theta, sine, sinc, half_sine, radius_here, scale, drop, px, py, pz;
};
template <class Real>
BentVertex<Real> spec_bend_vertex(Real center_distance, Real inv_radius, Real dx, Real dz,
                                  Real hc) {
  BentVertex<Real> v;
  v.rho = std::sqrt(dx * dx + dz * dz);
  v.theta = v.rho * inv_radius;
  Real cosine, half_cosine;
  spec_sincos<Real>(v.theta, v.sine, cosine, false);
  v.sinc = v.theta > Real(0) ? v.sine / v.theta : Real(1);
  spec_sincos<Real>(v.theta * Real(0.5), v.half_sine, half_cosine, false);  // sin_det
  v.radius_here = center_distance + hc;
  v.scale = (v.radius_here * inv_radius) * v.sinc;
  v.drop = v.radius_here * ((Real(2) * v.half_sine) * v.half_sine);
  v.px = dx * v.scale;
  v.pz = dz * v.scale;
  v.py = hc - v.drop;
  return v;
}

// bend_normals of one valid vertex off the nadir (rho > 0).
template <class Real>
struct BentNormal {
  Real rho, theta, sine, half_sine, cm1, ux, uz, along, delta, nx, ny, nz;
};
template <class Real>
BentNormal<Real> spec_bend_normal(Real inv_radius, Real dx, Real dz, Real nx, Real ny, Real nz) {
  BentNormal<Real> n;
  n.rho = std::sqrt(dx * dx + dz * dz);
  n.theta = n.rho * inv_radius;
  Real cosine, half_cosine;
  spec_sincos<Real>(n.theta, n.sine, cosine, false);                        // sin_det
  spec_sincos<Real>(n.theta * Real(0.5), n.half_sine, half_cosine, false);  // sin_det
  n.cm1 = (Real(-2) * n.half_sine) * n.half_sine;
  n.ux = dx / n.rho;
  n.uz = dz / n.rho;
  n.along = nx * n.ux + nz * n.uz;
  n.delta = n.along * n.cm1 + ny * n.sine;
  n.nx = nx + n.delta * n.ux;
  n.nz = nz + n.delta * n.uz;
  n.ny = (ny + ny * n.cm1) - n.along * n.sine;
  return n;
}

}  // namespace relief::test::worked
