#include "raster/clip.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace relief::raster {

namespace {

constexpr int kPlaneCount = 6;
enum Plane { kNear = 0, kFar = 1, kRight = 2, kLeft = 3, kTop = 4, kBottom = 5 };

float flush_denormal(float c) {
  // c * 0 keeps the sign, as the x86 DAZ flag does.
  return std::abs(c) < std::numeric_limits<float>::min() ? c * 0.0f : c;
}

double plane_distance(const PolygonVertex& v, int plane, double gx, double gy) {
  // For input vertices g w is exact in double (24-bit times 24-bit significand) and each
  // distance is one rounding of the exact one, so its sign is exact.
  switch (plane) {
    case kNear:
      return v.w - v.z;
    case kFar:
      return v.z;
    case kRight:
      return gx * v.w - v.x;
    case kLeft:
      return gx * v.w + v.x;
    case kTop:
      return gy * v.w - v.y;
    default:
      return gy * v.w + v.y;
  }
}

// The point where edge (s, e) meets `plane`; s is the end nearer to it (|d_s| <= |d_e|) and
// d_s, d_e have different signs.
PolygonVertex intersect(const PolygonVertex& s, const PolygonVertex& e, double ds, double de,
                        int plane, double gx, double gy) {
  // Division domain: d_s and d_e have different signs and |d_e| >= |d_s|, so d_e != 0 and
  // |d_s - d_e| = |d_s| + |d_e| > 0; t is in [0, 1/2] (rounding is monotonic).
  const double t = ds / (ds - de);
  PolygonVertex p{s.x + t * (e.x - s.x), s.y + t * (e.y - s.y), s.z + t * (e.z - s.z),
                  s.w + t * (e.w - s.w), -1};
  switch (plane) {
    case kNear:
      p.z = p.w;
      break;
    case kFar:
      // Both ends have w >= z (the near plane came first), so the exact w here is >= 0.
      p.z = 0.0;
      p.w = std::max(p.w, 0.0);
      break;
    case kRight:
      p.x = gx * p.w;
      break;
    case kLeft:
      p.x = -gx * p.w;
      break;
    case kTop:
      p.y = gy * p.w;
      break;
    default:
      p.y = -gy * p.w;
      break;
  }
  return p;
}

}  // namespace

bool prepare_clip_input(const ClipVertex in[3], ClipVertex out[3]) {
  bool all_ordinary = true;
  for (int k = 0; k < 3; ++k) {
    all_ordinary = all_ordinary && ordinary_clip_coordinate(in[k].x) &&
                   ordinary_clip_coordinate(in[k].y) && ordinary_clip_coordinate(in[k].z) &&
                   ordinary_clip_coordinate(in[k].w);
  }
  if (all_ordinary) {  // nothing to flush or reject but the origin
    for (int k = 0; k < 3; ++k) {
      out[k] = in[k];
      if (in[k].x == 0.0f && in[k].y == 0.0f && in[k].z == 0.0f && in[k].w == 0.0f) {
        return false;
      }
    }
    return true;
  }
  for (int k = 0; k < 3; ++k) {
    const ClipVertex& v = in[k];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w)) {
      return false;
    }
    out[k] = {flush_denormal(v.x), flush_denormal(v.y), flush_denormal(v.z), flush_denormal(v.w)};
    if (out[k].x == 0.0f && out[k].y == 0.0f && out[k].z == 0.0f && out[k].w == 0.0f) {
      return false;
    }
  }
  return true;
}

ClipOutcome clip_triangle(const ClipVertex in[3], const ClipPlanes& planes,
                          PolygonVertex out[kMaxClippedVertices], int& count) {
  const double gx = planes.guard_x;
  const double gy = planes.guard_y;
  const unsigned c0 = clip_outcode(in[0], planes), c1 = clip_outcode(in[1], planes),
                 c2 = clip_outcode(in[2], planes);
  if ((c0 & c1 & c2) != 0u) {  // all three outside one plane
    count = 0;
    return ClipOutcome::kOutside;
  }
  if ((c0 | c1 | c2) == 0u) {  // inside every plane
    count = 3;
    return ClipOutcome::kInside;
  }
  PolygonVertex buffer[2][kMaxClippedVertices];
  for (int k = 0; k < 3; ++k) {
    buffer[0][k] = {in[k].x, in[k].y, in[k].z, in[k].w, k};
  }
  // Every plane is applied, crossed or not: a plane no input vertex is outside of may still
  // see a new vertex a rounding error outside it, and applying it keeps the invariants above.
  int n = 3;
  int current = 0;
  for (int plane = 0; plane < kPlaneCount && n > 0; ++plane) {
    const PolygonVertex* src = buffer[current];
    PolygonVertex* dst = buffer[1 - current];
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const PolygonVertex& a = src[k];
      const PolygonVertex& b = src[(k + 1) % n];
      const double da = plane_distance(a, plane, gx, gy);
      const double db = plane_distance(b, plane, gx, gy);
      const bool a_in = da >= 0.0;
      const bool b_in = db >= 0.0;
      // A convex polygon gains at most one vertex per plane; one that rounding made
      // non-convex enough to gain more is numerically degenerate, and dropped (as Mesa's
      // clipper does when its vertex list would overflow).
      if (m + int(a_in) + int(a_in != b_in) > kMaxClippedVertices) {
        count = 0;
        return ClipOutcome::kClipped;
      }
      if (a_in) {
        dst[m++] = a;
      }
      if (a_in != b_in) {
        // From the end nearer to the plane; on a tie from the inside one. Symmetric in a, b.
        const double abs_a = std::abs(da), abs_b = std::abs(db);
        const bool from_a = abs_a < abs_b || (abs_a == abs_b && a_in);
        dst[m++] = from_a ? intersect(a, b, da, db, plane, gx, gy)
                          : intersect(b, a, db, da, plane, gx, gy);
      }
    }
    n = m;
    current = 1 - current;
  }
  // Only a vertex at the origin can have w = 0 here (see clip.h); it has no image.
  count = 0;
  for (int k = 0; k < n; ++k) {
    if (buffer[current][k].w > 0.0) {
      out[count++] = buffer[current][k];
    }
  }
  if (count < 3) {
    count = 0;
  }
  return ClipOutcome::kClipped;
}

}  // namespace relief::raster
