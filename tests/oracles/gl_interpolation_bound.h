// How far GL's interpolated value of a vertex attribute may lie from the CPU resolve's
// (raster/resolve.h: exact perspective-correct barycentrics in double, rounded once), and why
// (docs/gl-shading.md, "Thresholds"):
//   - the sample: a conforming GL may set its interpolation up from the vertices snapped to
//     1/256 px (each moved by up to 1/512 px in x and y), so its value is the exact one at a
//     point up to kSampleShift px from the pixel centre: kSampleShift (|da/dx| + |da/dy|);
//   - the arithmetic: GPUs and llvmpipe evaluate a/w and 1/w as planes p0 + px x + py y
//     referred to the framebuffer's origin, in float, then divide: each plane's rounding is a
//     few ulps of |p0| + |px x| + |py y|, which exceeds the plane's value where the pixel lies
//     far from the origin along a steep plane (terrain at grazing angles).
// Perspective-correct: a = A / W with A = sum of a_i / w_i and W = sum of 1 / w_i weighted
// by the screen-space barycentrics; both are affine in window x, y.
#pragma once

#include <cmath>

namespace relief::test {

inline constexpr double kSampleShift = 1.0 / 256.0;  // pixels
inline constexpr double kFloatEpsilon = 0x1.0p-24;   // a float rounding, relative
inline constexpr double kPlaneRoundings = 4.0;       // set-up and evaluation of a plane
inline constexpr double kValueUlps = 2.0;            // the final roundings to float

inline double float_ulp(double value) {
  const float f = std::abs(static_cast<float>(value));
  return double(std::nextafter(f, INFINITY)) - double(f);
}

// The plane v = p0 + px x + py y through three points (x_i, y_i, v_i); flat where degenerate.
struct Plane {
  double p0 = 0, px = 0, py = 0;

  Plane(const double x[3], const double y[3], const double v[3]) {
    const double ax = x[1] - x[0], ay = y[1] - y[0], av = v[1] - v[0];
    const double bx = x[2] - x[0], by = y[2] - y[0], bv = v[2] - v[0];
    const double nx = ay * bv - av * by, ny = av * bx - ax * bv, nz = ax * by - ay * bx;
    if (nz != 0.0) {
      px = -nx / nz;
      py = -ny / nz;
    }
    p0 = v[0] - px * x[0] - py * y[0];
  }
  double at(double u, double v) const { return p0 + px * u + py * v; }
  // The size of the terms a float evaluation from the origin rounds.
  double terms(double u, double v) const {
    return std::abs(p0) + std::abs(px * u) + std::abs(py * v);
  }
};

// A triangle in window coordinates: x, y in pixels, and 1 / w of each vertex (w > 0).
struct WindowTriangle {
  double x[3], y[3], inv_w[3];
};

// The two parts of a perspective-correct attribute's tolerance (vertex values a[3], at
// (u, v)): the sample's shift and the arithmetic (the planes' roundings and the final ones).
struct AttributeTolerance {
  double shift = INFINITY, rounding = INFINITY;  // infinite: not in front of the camera
};

inline AttributeTolerance attribute_parts(const WindowTriangle& t, const double a[3], double u,
                                          double v) {
  const double over_w[3] = {a[0] * t.inv_w[0], a[1] * t.inv_w[1], a[2] * t.inv_w[2]};
  const Plane top(t.x, t.y, over_w), bottom(t.x, t.y, t.inv_w);
  const double w_inv = bottom.at(u, v);
  if (!(w_inv > 0.0)) {
    return {};  // not in front of the camera here: nothing claimed
  }
  const double value = top.at(u, v) / w_inv;
  const double gx = (top.px - value * bottom.px) / w_inv;
  const double gy = (top.py - value * bottom.py) / w_inv;
  const double rounding = kPlaneRoundings * kFloatEpsilon *
                          (top.terms(u, v) + std::abs(value) * bottom.terms(u, v)) / w_inv;
  return {kSampleShift * (std::abs(gx) + std::abs(gy)), rounding + kValueUlps * float_ulp(value)};
}

// The tolerance for a perspective-correct attribute with vertex values a[3] at (u, v).
inline double attribute_tolerance(const WindowTriangle& t, const double a[3], double u, double v) {
  const AttributeTolerance parts = attribute_parts(t, a, u, v);
  return parts.shift + parts.rounding;
}

// Of attribute_tolerance, the arithmetic alone, without the sample's shift (which moves every
// attribute together along the surface).
inline double attribute_rounding(const WindowTriangle& t, const double a[3], double u, double v) {
  return attribute_parts(t, a, u, v).rounding;
}

// The tolerance for the window depth z/w, affine in x, y (depths z_i of the vertices).
inline double depth_tolerance(const WindowTriangle& t, const double z[3], double u, double v) {
  const Plane depth(t.x, t.y, z);
  return kSampleShift * (std::abs(depth.px) + std::abs(depth.py)) +
         kPlaneRoundings * kFloatEpsilon * depth.terms(u, v) +
         kValueUlps * float_ulp(depth.at(u, v));
}

}  // namespace relief::test
