// The exact image of a clip-space triangle, for the clipping and accuracy tests: the float clip
// coordinates are taken as exact and clipped, projected and interpolated in long double (64
// significant bits on x86-64, 113 on AArch64 Linux; 2^-64 relative is far below every bound
// the tests check). Also the randomised near-plane set shared by the GL-free and GL tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/counter_hash.h"
#include "raster/clip.h"
#include "raster/raster_types.h"
#include "tests/support/hashed_draws.h"

namespace relief::test {

using Exact = long double;
static_assert(std::numeric_limits<Exact>::digits >= 64, "the reference needs extended precision");

class ExactTriangle {
 public:
  // GL's input rules are part of the definition (raster/clip.h): denormals are zero, and a
  // vertex at the origin or a non-finite coordinate leaves nothing. The polygon is clipped
  // against near, far and the viewport's sides (|x|, |y| <= w): what a rasteriser draws inside
  // the viewport does not depend on where outside it x and y are clipped.
  ExactTriangle(const raster::ClipVertex v[3], const raster::Viewport& viewport) {
    sx_ = Exact(viewport.width) / 2;
    sy_ = Exact(viewport.height) / 2;
    tx_ = Exact(viewport.x) + sx_;
    ty_ = Exact(viewport.y) + sy_;
    std::vector<H> poly;
    for (int k = 0; k < 3; ++k) {
      const H h{flush(v[k].x), flush(v[k].y), flush(v[k].z), flush(v[k].w)};
      if (!std::isfinite(h.x) || !std::isfinite(h.y) || !std::isfinite(h.z) ||
          !std::isfinite(h.w) || (h.x == 0 && h.y == 0 && h.z == 0 && h.w == 0)) {
        return;
      }
      // Homogeneous window coordinates of the whole triangle, for depth and barycentrics.
      X_[k] = h.x * sx_ + h.w * tx_;
      Y_[k] = h.y * sy_ + h.w * ty_;
      Z_[k] = h.z;
      W_[k] = h.w;
      poly.push_back(h);
    }
    for (int plane = 0; plane < 6 && poly.size() >= 3; ++plane) {
      poly = clip(poly, plane);
    }
    for (const H& h : poly) {
      if (h.w > 0) {  // division domain; w = 0 is left only at the origin, which has no image
        px_.push_back(h.x / h.w * sx_ + tx_);
        py_.push_back(h.y / h.w * sy_ + ty_);
      }
    }
    Exact area = 0;
    const std::size_t n = px_.size();
    for (std::size_t k = 0; k < n; ++k) {
      area += px_[k] * py_[(k + 1) % n] - px_[(k + 1) % n] * py_[k];
    }
    orientation_ = area > 0 ? 1 : (area < 0 ? -1 : 0);
    if (n < 3) {
      orientation_ = 0;
    }
  }

  bool empty() const { return orientation_ == 0; }

  // Distance in pixels of window point (u, v) from the image's boundary, negative inside; for
  // a point outside, the largest distance outside one edge's line (a lower bound).
  Exact signed_distance(Exact u, Exact v) const {
    if (empty()) {
      return std::numeric_limits<Exact>::infinity();
    }
    Exact d = -std::numeric_limits<Exact>::infinity();
    const std::size_t n = px_.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Exact ex = px_[(k + 1) % n] - px_[k], ey = py_[(k + 1) % n] - py_[k];
      const Exact length = std::sqrt(ex * ex + ey * ey);  // domain: >= 0; 0 skips the edge
      if (length > 0) {
        d = std::max(d, orientation_ * ((u - px_[k]) * ey - (v - py_[k]) * ex) / length);
      }
    }
    return d;
  }

  // Perspective-correct barycentrics (the weights of clip-space interpolation) and depth z/w
  // of the whole triangle's plane at window point (u, v) (2D homogeneous rasterisation,
  // Olano & Greer 1997); false where the ray is parallel to the plane.
  bool interpolate(Exact u, Exact v, Exact b[3], Exact& depth) const {
    Exact l[3], sum = 0, sum_z = 0, sum_w = 0;
    for (int i = 0; i < 3; ++i) {
      const int a = (i + 1) % 3, c = (i + 2) % 3;
      l[i] = (X_[a] - u * W_[a]) * (Y_[c] - v * W_[c]) - (Y_[a] - v * W_[a]) * (X_[c] - u * W_[c]);
      sum += l[i];
      sum_z += l[i] * Z_[i];
      sum_w += l[i] * W_[i];
    }
    if (sum == 0 || sum_w == 0) {  // the divisions' domain
      return false;
    }
    for (int i = 0; i < 3; ++i) {
      b[i] = l[i] / sum;
    }
    depth = std::clamp(sum_z / sum_w, Exact(0), Exact(1));
    return true;
  }

 private:
  struct H {
    Exact x, y, z, w;
  };
  static Exact flush(float c) {
    return std::abs(c) < std::numeric_limits<float>::min() ? Exact(0) : Exact(c);
  }
  static Exact distance(const H& h, int plane) {
    switch (plane) {
      case 0:
        return h.w - h.z;
      case 1:
        return h.z;
      case 2:
        return h.w - h.x;
      case 3:
        return h.w + h.x;
      case 4:
        return h.w - h.y;
      default:
        return h.w + h.y;
    }
  }
  static std::vector<H> clip(const std::vector<H>& poly, int plane) {
    std::vector<H> out;
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
      const H& a = poly[k];
      const H& b = poly[(k + 1) % n];
      const Exact da = distance(a, plane), db = distance(b, plane);
      if (da >= 0) {
        out.push_back(a);
      }
      if ((da >= 0) != (db >= 0)) {
        // From the nearer end, so that t <= 1/2 (domain: da, db differ in sign).
        const bool from_a = std::abs(da) <= std::abs(db);
        const H& s = from_a ? a : b;
        const H& e = from_a ? b : a;
        const Exact ds = from_a ? da : db, de = from_a ? db : da;
        const Exact t = ds / (ds - de);
        out.push_back({s.x + t * (e.x - s.x), s.y + t * (e.y - s.y), s.z + t * (e.z - s.z),
                       s.w + t * (e.w - s.w)});
      }
    }
    return out;
  }

  Exact sx_ = 1, sy_ = 1, tx_ = 0, ty_ = 0;
  Exact X_[3] = {}, Y_[3] = {}, Z_[3] = {}, W_[3] = {};
  std::vector<Exact> px_, py_;  // the clipped image in window coordinates
  int orientation_ = 0;
};

// Triangle `index` of the randomised near-plane set: one or two vertices in front of the near
// plane, the others behind it (between the eye and the near plane, or behind the eye, where
// z may also cross the far plane), in a random order; |w| log-uniform in [1e-6, 1e13] per
// vertex. Vertices in front project into [-W, 2W] x [-H, 2H] px around the framebuffer.
inline void near_plane_triangle(std::uint64_t index, int width, int height,
                                const raster::Viewport& viewport, raster::ClipVertex v[3]) {
  const std::uint64_t key = index * 64;
  const double sx = viewport.width / 2, sy = viewport.height / 2;  // > 0: divided by below
  const double tx = viewport.x + sx, ty = viewport.y + sy;
  const int in_front = hashed_uniform(key, 0, 1) < 0.5 ? 1 : 2;
  const int first = static_cast<int>(hashed_uniform(key + 1, 0, 3));
  for (int k = 0; k < 3; ++k) {
    const std::uint64_t vk = key + 8 * (k + 1);
    const double w = std::pow(10.0, hashed_uniform(vk, -6, 13));
    const double nx = (hashed_uniform(vk + 1, -width, 2.0 * width) - tx) / sx;
    const double ny = (hashed_uniform(vk + 2, -height, 2.0 * height) - ty) / sy;
    const double u = hashed_uniform(vk + 3, 0, 1);
    if ((k - first + 3) % 3 < in_front) {
      v[k] = {float(nx * w), float(ny * w), float(u * w), float(w)};
    } else if (hashed_uniform(vk + 4, 0, 1) < 0.5) {
      v[k] = {float(nx * w), float(ny * w), float(w * (1 + 3 * u)), float(w)};  // z > w > 0
    } else {
      v[k] = {float(nx * w), float(ny * w), float(-w + w * 2 * u), float(-w)};  // behind the eye
    }
  }
}

}  // namespace relief::test
