#include "raster/triangle_setup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>

#include "raster/setup_internal.h"

namespace relief::raster {

using namespace setup_detail;

std::int32_t snap_to_fixed(float window_coordinate) {
  const float scaled = (window_coordinate - 0.5f) * static_cast<float>(kSubpixelScale);
  return round_half_even(static_cast<double>(scaled));
}

std::int32_t snap_double_to_fixed(double window_coordinate) {
  return round_half_even((window_coordinate - 0.5) * kSubpixelScale);
}

TriangleSetup::TriangleSetup(const RasterState& state) {
  const Viewport& vp = state.viewport;
  scale_x_ = static_cast<float>(vp.width * 0.5);
  scale_y_ = static_cast<float>(vp.height * 0.5);
  translate_x_ = static_cast<float>(vp.x + vp.width * 0.5);
  translate_y_ = static_cast<float>(vp.y + vp.height * 0.5);
  // GL's face culling: front faces are those of the front_face winding.
  const bool ccw_front = state.front_face == FrontFace::kCounterClockwise;
  edge_rules_.cull_counter_clockwise = (state.cull == CullMode::kBack && !ccw_front) ||
                                       (state.cull == CullMode::kFront && ccw_front);
  edge_rules_.cull_clockwise = (state.cull == CullMode::kBack && ccw_front) ||
                               (state.cull == CullMode::kFront && !ccw_front);
  planes_.guard_x = static_cast<float>((kGuardBandPixels - std::abs(translate_x_)) / scale_x_);
  planes_.guard_y = static_cast<float>((kGuardBandPixels - std::abs(translate_y_)) / scale_y_);
  // Pixels whose centres lie inside both the viewport and the framebuffer.
  edge_rules_.region_x0 = std::max(0, static_cast<int>(std::ceil(vp.x - 0.5)));
  edge_rules_.region_y0 = std::max(0, static_cast<int>(std::ceil(vp.y - 0.5)));
  edge_rules_.region_x1 =
      std::min(state.width, static_cast<int>(std::ceil(vp.x + vp.width - 0.5))) - 1;
  edge_rules_.region_y1 =
      std::min(state.height, static_cast<int>(std::ceil(vp.y + vp.height - 0.5))) - 1;
}

void TriangleSetup::to_window(const ClipVertex& v, float& x, float& y, float& z) const {
  const float inv_w = 1.0f / v.w;  // w > 0 and normal (denormals flushed): 1/w is finite
  x = v.x * inv_w * scale_x_ + translate_x_;
  y = v.y * inv_w * scale_y_ + translate_y_;
  z = v.z * inv_w;  // glDepthRange(0, 1), GL_ZERO_TO_ONE
}

void TriangleSetup::to_window(const PolygonVertex& v, double& x, double& y) const {
  // Division domain: w > 0, and |x|, |y| <= g w up to a few ulps, so the quotients are finite
  // and bounded by the guard band.
  x = v.x / v.w * double(scale_x_) + double(translate_x_);
  y = v.y / v.w * double(scale_y_) + double(translate_y_);
}

void TriangleSetup::setup_clip(std::uint32_t primitive, const ClipVertex v_in[3],
                               std::vector<RasterTriangle>& out) const {
  ClipVertex v[3];
  if (!prepare_clip_input(v_in, v)) {
    return;
  }
  PolygonVertex polygon[kMaxClippedVertices];
  int count = 0;
  const ClipOutcome outcome = clip_triangle(v, planes_, polygon, count);
  if (outcome == ClipOutcome::kOutside) {
    return;
  }
  if (outcome == ClipOutcome::kInside) {
    for (int k = 0; k < 3; ++k) {
      polygon[k].source = k;  // input vertices: only `source` is read
    }
  }
  setup_polygon(primitive, v, polygon, count, out);
}

void TriangleSetup::setup_polygon(std::uint32_t primitive, const ClipVertex v[3],
                                  const PolygonVertex polygon[kMaxClippedVertices], int count,
                                  std::vector<RasterTriangle>& out) const {
  if (count < 3) {
    return;
  }
  // Input vertices get their float window coordinates, as GL computes them: bit for bit the
  // same in every triangle sharing them, clipped or not, so a mesh stays watertight. New
  // vertices are snapped from double.
  std::int32_t fx[kMaxClippedVertices], fy[kMaxClippedVertices];
  double first_x = 0, first_y = 0, first_z = 0;
  for (int k = 0; k < count; ++k) {
    double x, y, z;
    if (polygon[k].source >= 0) {
      float xf, yf, zf;
      to_window(v[polygon[k].source], xf, yf, zf);
      x = xf, y = yf, z = zf;
    } else {
      to_window(polygon[k], x, y);
      z = polygon[k].z / polygon[k].w;  // domain: w > 0 (clip_triangle)
    }
    if (!(std::abs(x) < kSnapLimitPixels && std::abs(y) < kSnapLimitPixels)) {
      return;  // unreachable while clip_triangle's invariants hold (clip.h)
    }
    fx[k] = polygon[k].source >= 0 ? snap_to_fixed(float(x)) : snap_double_to_fixed(x);
    fy[k] = polygon[k].source >= 0 ? snap_to_fixed(float(y)) : snap_double_to_fixed(y);
    if (k == 0) {
      first_x = x, first_y = y, first_z = z;
    }
  }
  // A clipped polygon is convex: a fan from its first vertex covers it exactly once.
  bool have_plane = false;
  double z0 = 0.0, dzdx = 0.0, dzdy = 0.0;
  for (int k = 1; k + 1 < count; ++k) {
    std::int32_t px[3] = {fx[0], fx[k], fx[k + 1]};
    std::int32_t py[3] = {fy[0], fy[k], fy[k + 1]};
    RasterTriangle t;
    bool swapped = false;
    if (!set_up_edges(px, py, t, swapped)) {
      continue;
    }
    if (!have_plane) {
      // The depth plane of the whole triangle (once, for the first piece that covers a pixel).
      have_plane = true;
      piece_depth(v, first_x, first_y, first_z, z0, dzdx, dzdy);
    }
    t.z0 = z0;
    t.dzdx = dzdx;
    t.dzdy = dzdy;
    t.primitive = primitive;
    out.push_back(t);
  }
}

void TriangleSetup::piece_depth(const ClipVertex v[3], double first_x, double first_y,
                                double first_z, double& z0, double& dzdx, double& dzdy) const {
  // Referred to a whole pixel at the polygon's first vertex so that its coefficients suffer no
  // cancellation against a distant window origin.
  const double u0 = std::floor(first_x), v0 = std::floor(first_y);
  double z_ref = first_z;
  if (!depth_plane(v, u0, v0, z_ref, dzdx, dzdy)) {
    z_ref = first_z;  // seen edge-on: any piece left by rounding gets a constant depth
    dzdx = dzdy = 0.0;
  }
  z0 = z_ref + dzdx * (0.5 - u0) + dzdy * (0.5 - v0);
}

bool TriangleSetup::depth_plane(const ClipVertex v[3], double u0, double v0, double& z_ref,
                                double& dzdx, double& dzdy) const {
  // Homogeneous window coordinates relative to (u0, v0): X = x s_x + w (t_x - u0), Y likewise,
  // Z = z, W = w. The triangle spans a 3D subspace of (X, Y, Z, W) space whose normal n is the
  // generalised cross product of the three rows (its 3 x 3 minors); on the ray of window point
  // (u0 + a, v0 + b), X = a W and Y = b W, so n_X a + n_Y b + n_Z z + n_W = 0 with z = Z/W.
  // Range: |X|, |Y| < 2^25 * 3.4e38 for viewports below 2^24 px (the guard band keeps
  // |t_x - u0| below 2^22), so products of three stay below 1e140; nonzero float inputs
  // (denormals flushed) are above 1e-38, products above 1e-114: double neither overflows nor
  // underflows, and its rounding is relative.
  const double cx = double(translate_x_) - u0;  // exact: integers and floats below 2^24
  const double cy = double(translate_y_) - v0;
  double X[3], Y[3], Z[3], W[3];
  for (int k = 0; k < 3; ++k) {
    X[k] = double(v[k].x) * double(scale_x_) + double(v[k].w) * cx;
    Y[k] = double(v[k].y) * double(scale_y_) + double(v[k].w) * cy;
    Z[k] = v[k].z;
    W[k] = v[k].w;
  }
  const double n_x = det3(Y, Z, W);
  const double n_y = -det3(X, Z, W);
  const double n_z = det3(X, Y, W);
  const double n_w = -det3(X, Y, Z);
  // Division domain: n_z != 0, i.e. the triangle's image has area (n_z is proportional to its
  // signed area in homogeneous window coordinates); else no plane z(x, y) exists.
  if (!(std::abs(n_z) > 0.0)) {
    return false;
  }
  dzdx = -n_x / n_z;
  dzdy = -n_y / n_z;
  z_ref = -n_w / n_z;
  return std::isfinite(dzdx) && std::isfinite(dzdy) && std::isfinite(z_ref);
}

void TriangleSetup::setup_window(std::uint32_t primitive, const float x_in[3], const float y_in[3],
                                 const float z_in[3], std::vector<RasterTriangle>& out) const {
  float x[3] = {x_in[0], x_in[1], x_in[2]};
  float y[3] = {y_in[0], y_in[1], y_in[2]};
  float z[3] = {z_in[0], z_in[1], z_in[2]};
  std::int32_t fx[3], fy[3];
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(x[k]) < kSnapLimitPixels && std::abs(y[k]) < kSnapLimitPixels)) {
      return;  // outside the precondition: dropped rather than snapped out of range
    }
    fx[k] = snap_to_fixed(x[k]);
    fy[k] = snap_to_fixed(y[k]);
  }
  RasterTriangle t;
  bool swapped = false;
  if (!set_up_edges(fx, fy, t, swapped)) {
    return;
  }
  if (swapped) {
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
    std::swap(z[1], z[2]);
  }
  // Depth plane through the window-space vertices. Division domain: det != 0, else a
  // constant plane (the snapped triangle has area, but its float vertices are collinear).
  const double ex = double(x[1]) - x[0], ey = double(y[1]) - y[0], ez = double(z[1]) - z[0];
  const double gx = double(x[2]) - x[0], gy = double(y[2]) - y[0], gz = double(z[2]) - z[0];
  const double det = ex * gy - gx * ey;
  t.dzdx = det != 0.0 ? (ez * gy - gz * ey) / det : 0.0;
  t.dzdy = det != 0.0 ? (ex * gz - gx * ez) / det : 0.0;
  t.z0 = double(z[0]) + t.dzdx * (0.5 - double(x[0])) + t.dzdy * (0.5 - double(y[0]));
  t.primitive = primitive;
  out.push_back(t);
}

bool TriangleSetup::set_up_edges(std::int32_t fx[3], std::int32_t fy[3], RasterTriangle& t,
                                 bool& swapped) const {
  std::int32_t box[4];
  if (!edge_box(edge_rules_, fx, fy, box, swapped)) {
    return false;
  }
  write_edges(fx, fy, box, t);
  return true;
}

}  // namespace relief::raster
