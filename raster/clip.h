// Homogeneous clipping (Sutherland-Hodgman) for the few triangles that need it.
//
// Planes, as distances that are >= 0 inside:
//   near   w - z        (GL_ZERO_TO_ONE: z_ndc <= 1)
//   far    z            (z_ndc >= 0; the infinite reverse-Z projection never reaches it, but
//                        triangle soups may)
//   guard  g_x w -+ x, g_y w -+ y   (the guard band: window coordinates within
//                        kGuardBandPixels; raster_types.h)
// Triangles inside every plane are not clipped (the guard band makes that the rule: only
// those crossing the near or far plane, or reaching millions of pixels off screen, are).
// Triangles entirely outside one plane are rejected. New vertices are in + t (out - in),
// t = d_in / (d_in - d_out), in float as GL implementations compute them.
#pragma once

namespace relief::raster {

struct ClipVertex {
  float x, y, z, w;
};

// 3 input vertices plus one per plane at most.
inline constexpr int kMaxClippedVertices = 9;

struct ClipPlanes {
  float guard_x;  // |x| <= guard_x w keeps the window x inside the guard band
  float guard_y;
};

enum class ClipOutcome { kInside, kOutside, kClipped };

// Classifies the triangle; when it must be clipped, writes the convex polygon (in the input's
// winding) to `out` and its vertex count (0 when nothing is left) to `count`.
ClipOutcome clip_triangle(const ClipVertex in[3], const ClipPlanes& planes,
                          ClipVertex out[kMaxClippedVertices], int& count);

}  // namespace relief::raster
