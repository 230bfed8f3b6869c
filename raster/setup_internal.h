// Pieces of the triangle set-up shared by its per-triangle path (triangle_setup.cc) and its
// grid walker (grid_setup.cc): fixed-point rounding, the edge set-up and the 3 x 3
// determinants of the depth plane.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "raster/triangle_setup.h"

namespace relief::raster::setup_detail {

// floor(a / 256) and ceil(a / 256) for any sign: C++20 defines a >> n for negative a as
// a / 2^n rounded toward negative infinity (arithmetic shift), which is floor(a / 256) for
// n = 8; ceil(a / 256) = -floor(-a / 256). |a| < 2^31 here, so -a cannot overflow.
inline std::int64_t floor_div(std::int64_t a) {
  return a >> kSubpixelBits;
}
inline std::int64_t ceil_div(std::int64_t a) {
  return -floor_div(-a);
}

// Round half to even, exactly, without a libm call: adding and removing 1.5 * 2^52 in double
// leaves the nearest integer (ties to even) for |scaled| < 2^51; the guard band keeps |scaled|
// below 2^30.
inline std::int32_t round_half_even(double scaled) {
  constexpr double kRoundingMagic = 6755399441055744.0;  // 1.5 * 2^52
  return static_cast<std::int32_t>((scaled + kRoundingMagic) - kRoundingMagic);
}

// set_up_edges in two halves, for setup_grid to use apart. The first: culling (zero area, the
// state's face culling) and the pixel bounds (x0, y0, x1, y1) within the region, the vertices
// made counter-clockwise (`swapped`: 1 and 2 exchanged); false when the triangle is culled or
// covers no pixel centre of the region.
inline bool edge_box(const EdgeRules& rules, std::int32_t fx[3], std::int32_t fy[3],
                     std::int32_t box[4], bool& swapped) {
  const std::int64_t area = static_cast<std::int64_t>(fx[1] - fx[0]) * (fy[2] - fy[0]) -
                            static_cast<std::int64_t>(fx[2] - fx[0]) * (fy[1] - fy[0]);
  if (area == 0) {
    return false;  // zero-area triangles produce nothing
  }
  const bool counter_clockwise = area > 0;
  if (counter_clockwise ? rules.cull_counter_clockwise : rules.cull_clockwise) {
    return false;
  }
  swapped = !counter_clockwise;
  if (swapped) {
    std::swap(fx[1], fx[2]);
    std::swap(fy[1], fy[2]);
  }
  const std::int64_t min_x = std::min({fx[0], fx[1], fx[2]});
  const std::int64_t max_x = std::max({fx[0], fx[1], fx[2]});
  const std::int64_t min_y = std::min({fy[0], fy[1], fy[2]});
  const std::int64_t max_y = std::max({fy[0], fy[1], fy[2]});
  box[0] = static_cast<std::int32_t>(std::max<std::int64_t>(ceil_div(min_x), rules.region_x0));
  box[1] = static_cast<std::int32_t>(std::max<std::int64_t>(ceil_div(min_y), rules.region_y0));
  box[2] = static_cast<std::int32_t>(std::min<std::int64_t>(floor_div(max_x), rules.region_x1));
  box[3] = static_cast<std::int32_t>(std::min<std::int64_t>(floor_div(max_y), rules.region_y1));
  return box[0] <= box[2] && box[1] <= box[3];
}

// The second: bounds and edge functions of the (counter-clockwise) triangle into `t`.
inline void write_edges(const std::int32_t fx[3], const std::int32_t fy[3],
                        const std::int32_t box[4], RasterTriangle& t) {
  t.x0 = box[0];
  t.y0 = box[1];
  t.x1 = box[2];
  t.y1 = box[3];
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
}

// 3 x 3 determinant of the columns p, q, r (rows: the triangle's vertices).
inline double det3(const double p[3], const double q[3], const double r[3]) {
  return p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
         p[2] * (q[0] * r[1] - q[1] * r[0]);
}

// Window coordinates of polygon vertices are checked against this before snapping: the
// clipper keeps them within the guard band (2^21 px) up to a few ulps (float ones up to half
// an ulp of 2^21 more), and the edge set-up needs snapped differences below 2^31. A vertex
// beyond it would mean a broken invariant: the triangle is dropped rather than snapped.
constexpr double kSnapLimitPixels = kGuardBandPixels + 1.0;

}  // namespace relief::raster::setup_detail
