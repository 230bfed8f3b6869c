#include "raster/triangle_setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace relief::raster {

namespace {

// floor(a / 256) and ceil(a / 256) for any sign (C++ division truncates toward zero).
std::int64_t floor_div(std::int64_t a) {
  return a >= 0 ? a / kSubpixelScale : -((-a + kSubpixelScale - 1) / kSubpixelScale);
}
std::int64_t ceil_div(std::int64_t a) {
  return -floor_div(-a);
}

}  // namespace

std::int32_t snap_to_fixed(float window_coordinate) {
  const float scaled = (window_coordinate - 0.5f) * static_cast<float>(kSubpixelScale);
  // Round half to even, exactly, without a libm call: adding and removing 1.5 * 2^52 in
  // double leaves the nearest integer (ties to even) for |scaled| < 2^51; the guard band keeps
  // |scaled| below 2^30.
  constexpr double kRoundingMagic = 6755399441055744.0;  // 1.5 * 2^52
  const double rounded = (static_cast<double>(scaled) + kRoundingMagic) - kRoundingMagic;
  return static_cast<std::int32_t>(rounded);
}

TriangleSetup::TriangleSetup(const RasterState& state) : state_(state) {
  const Viewport& vp = state.viewport;
  scale_x_ = static_cast<float>(vp.width * 0.5);
  scale_y_ = static_cast<float>(vp.height * 0.5);
  translate_x_ = static_cast<float>(vp.x + vp.width * 0.5);
  translate_y_ = static_cast<float>(vp.y + vp.height * 0.5);
  planes_.guard_x = static_cast<float>((kGuardBandPixels - std::abs(translate_x_)) / scale_x_);
  planes_.guard_y = static_cast<float>((kGuardBandPixels - std::abs(translate_y_)) / scale_y_);
  // Pixels whose centres lie inside both the viewport and the framebuffer.
  region_x0_ = std::max(0, static_cast<int>(std::ceil(vp.x - 0.5)));
  region_y0_ = std::max(0, static_cast<int>(std::ceil(vp.y - 0.5)));
  region_x1_ = std::min(state.width, static_cast<int>(std::ceil(vp.x + vp.width - 0.5))) - 1;
  region_y1_ = std::min(state.height, static_cast<int>(std::ceil(vp.y + vp.height - 0.5))) - 1;
}

void TriangleSetup::to_window(const ClipVertex& v, float& x, float& y, float& z) const {
  const float inv_w = 1.0f / v.w;  // w > 0 after clipping against the near plane
  x = v.x * inv_w * scale_x_ + translate_x_;
  y = v.y * inv_w * scale_y_ + translate_y_;
  z = v.z * inv_w;  // glDepthRange(0, 1), GL_ZERO_TO_ONE
}

void TriangleSetup::setup_clip(std::uint32_t primitive, const ClipVertex v[3],
                               std::vector<RasterTriangle>& out) const {
  ClipVertex polygon[kMaxClippedVertices];
  int count = 0;
  const ClipOutcome outcome = clip_triangle(v, planes_, polygon, count);
  if (outcome == ClipOutcome::kOutside) {
    return;
  }
  const ClipVertex* vertices = outcome == ClipOutcome::kInside ? v : polygon;
  float wx[kMaxClippedVertices], wy[kMaxClippedVertices], wz[kMaxClippedVertices];
  for (int k = 0; k < count; ++k) {
    to_window(vertices[k], wx[k], wy[k], wz[k]);
  }
  // A clipped polygon is convex: a fan from its first vertex covers it exactly once.
  for (int k = 1; k + 1 < count; ++k) {
    const float x[3] = {wx[0], wx[k], wx[k + 1]};
    const float y[3] = {wy[0], wy[k], wy[k + 1]};
    const float z[3] = {wz[0], wz[k], wz[k + 1]};
    setup_window(primitive, x, y, z, out);
  }
}

void TriangleSetup::setup_window(std::uint32_t primitive, const float x_in[3], const float y_in[3],
                                 const float z_in[3], std::vector<RasterTriangle>& out) const {
  float x[3] = {x_in[0], x_in[1], x_in[2]};
  float y[3] = {y_in[0], y_in[1], y_in[2]};
  float z[3] = {z_in[0], z_in[1], z_in[2]};
  std::int32_t fx[3], fy[3];
  for (int k = 0; k < 3; ++k) {
    fx[k] = snap_to_fixed(x[k]);
    fy[k] = snap_to_fixed(y[k]);
  }
  const std::int64_t area = static_cast<std::int64_t>(fx[1] - fx[0]) * (fy[2] - fy[0]) -
                            static_cast<std::int64_t>(fx[2] - fx[0]) * (fy[1] - fy[0]);
  if (area == 0) {
    return;  // zero-area triangles produce nothing
  }
  const bool counter_clockwise = area > 0;
  const bool front = counter_clockwise == (state_.front_face == FrontFace::kCounterClockwise);
  if ((state_.cull == CullMode::kBack && !front) || (state_.cull == CullMode::kFront && front)) {
    return;
  }
  if (!counter_clockwise) {
    std::swap(fx[1], fx[2]);
    std::swap(fy[1], fy[2]);
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
    std::swap(z[1], z[2]);
  }
  RasterTriangle t;
  const std::int64_t min_x = std::min({fx[0], fx[1], fx[2]});
  const std::int64_t max_x = std::max({fx[0], fx[1], fx[2]});
  const std::int64_t min_y = std::min({fy[0], fy[1], fy[2]});
  const std::int64_t max_y = std::max({fy[0], fy[1], fy[2]});
  t.x0 = static_cast<std::int32_t>(std::max<std::int64_t>(ceil_div(min_x), region_x0_));
  t.x1 = static_cast<std::int32_t>(std::min<std::int64_t>(floor_div(max_x), region_x1_));
  t.y0 = static_cast<std::int32_t>(std::max<std::int64_t>(ceil_div(min_y), region_y0_));
  t.y1 = static_cast<std::int32_t>(std::min<std::int64_t>(floor_div(max_y), region_y1_));
  if (t.x0 > t.x1 || t.y0 > t.y1) {
    return;
  }
  for (int i = 0; i < 3; ++i) {
    const int n = (i + 1) % 3;
    const std::int32_t dx = fx[n] - fx[i];
    const std::int32_t dy = fy[n] - fy[i];
    t.a[i] = -dy;
    t.b[i] = dx;
    const bool left_or_bottom = dy < 0 || (dy == 0 && dx > 0);
    t.c[i] =
        -(static_cast<std::int64_t>(t.a[i]) * fx[i] + static_cast<std::int64_t>(t.b[i]) * fy[i]) +
        (left_or_bottom ? 1 : 0);
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

}  // namespace relief::raster
