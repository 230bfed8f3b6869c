#include "raster/clip.h"

#include <algorithm>

namespace relief::raster {

namespace {

constexpr int kPlaneCount = 6;

float plane_distance(const ClipVertex& v, int plane, const ClipPlanes& p) {
  switch (plane) {
    case 0:
      return v.w - v.z;  // near
    case 1:
      return v.z;  // far
    case 2:
      return p.guard_x * v.w - v.x;
    case 3:
      return p.guard_x * v.w + v.x;
    case 4:
      return p.guard_y * v.w - v.y;
    default:
      return p.guard_y * v.w + v.y;
  }
}

ClipVertex interpolate(const ClipVertex& in, const ClipVertex& out, float t) {
  return {in.x + t * (out.x - in.x), in.y + t * (out.y - in.y), in.z + t * (out.z - in.z),
          in.w + t * (out.w - in.w)};
}

}  // namespace

ClipOutcome clip_triangle(const ClipVertex in[3], const ClipPlanes& planes,
                          ClipVertex out[kMaxClippedVertices], int& count) {
  unsigned crossing = 0;  // planes some vertex is outside of
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    int outside = 0;
    for (int k = 0; k < 3; ++k) {
      // NaN distances count as outside: a vertex with a NaN coordinate is never drawn.
      outside += !(plane_distance(in[k], plane, planes) >= 0.0f);
    }
    if (outside == 3) {
      count = 0;
      return ClipOutcome::kOutside;
    }
    if (outside > 0) {
      crossing |= 1u << plane;
    }
  }
  if (crossing == 0) {
    count = 3;
    return ClipOutcome::kInside;
  }
  ClipVertex buffer[2][kMaxClippedVertices];
  std::copy(in, in + 3, buffer[0]);
  int n = 3;
  int current = 0;
  for (int plane = 0; plane < kPlaneCount && n > 0; ++plane) {
    if (!(crossing & (1u << plane))) {
      continue;
    }
    const ClipVertex* src = buffer[current];
    ClipVertex* dst = buffer[1 - current];
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const ClipVertex& a = src[k];
      const ClipVertex& b = src[(k + 1) % n];
      const float da = plane_distance(a, plane, planes);
      const float db = plane_distance(b, plane, planes);
      const bool a_in = da >= 0.0f;
      const bool b_in = db >= 0.0f;
      if (a_in) {
        dst[m++] = a;
      }
      if (a_in != b_in) {
        // Division domain: da and db have different signs (one may be zero only on the
        // inside), so da - db != 0. Interpolate from the inside vertex.
        dst[m++] = a_in ? interpolate(a, b, da / (da - db)) : interpolate(b, a, db / (db - da));
      }
    }
    n = m;
    current = 1 - current;
  }
  count = n >= 3 ? n : 0;
  std::copy(buffer[current], buffer[current] + count, out);
  return ClipOutcome::kClipped;
}

}  // namespace relief::raster
