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
// Triangles entirely outside one plane are rejected.
//
// The clipper works in double: finite float coordinates (denormals flushed: 1e-38 to 3.4e38)
// and the guard factors (below 2^22) neither overflow nor underflow there, and every rounding
// is relative, so one triangle may mix any magnitudes. Classification is exact: each distance
// of an input vertex is one rounding of the exact value, which keeps its sign.
//
// A new vertex is interpolated from the end nearer to the plane, P = S + t (E - S) with
// t = d_S / (d_S - d_E) in [0, 1/2], as Mesa's draw module does (draw_pipe_clip.c; llvmpipe
// 22.3 draws such triangles as exact arithmetic does): interpolating from a fixed end makes t
// round to 1 and P collapse onto the other end, w = 0 included, when the distances differ by
// orders of magnitude. The choice depends only on the edge's two vertices, never on the
// direction it is walked in, so triangles sharing an edge get bit-identical new vertices (no
// cracks). P is then put exactly on the plane (near: z = w; far: z = 0, w >= 0; guard:
// x = +-g_x w, y = +-g_y w). A clipped triangle meets every plane, in the order near, far,
// guards: after the far plane every vertex has 0 <= z <= w exactly, and the guard planes keep
// w >= 0 (rounding is monotonic; t <= 1/2). w = 0 is then left only for a vertex at the
// origin, which has no window position: in exact arithmetic that happens only when the
// triangle is seen edge-on (its image is a line), so the vertex is dropped and the polygon is
// the convex hull of the others. Every remaining vertex has w > 0, |x| <= g_x w and
// |y| <= g_y w up to a few ulps: finite window coordinates inside the guard band.
#pragma once

#include <bit>
#include <cstdint>

namespace relief::raster {

struct ClipVertex {
  float x, y, z, w;
};

// GL's rules for what reaches the clipper, applied to `in` (written to `out`); false when the
// triangle draws nothing whatever its position:
// - denormal coordinates are flushed to zero (sign kept): GLSL 4.50 section 4.7.1 allows it,
//   Mesa's draw module runs with denormals-are-zero, and GPUs flush fp32 denormals in vertex
//   shaders; so a vertex of denormals is the origin, as on the GPU;
// - a non-finite coordinate rejects the triangle (Mesa's clipper discards NaN and infinite
//   plane distances; Relief rejects them before any plane is evaluated);
// - a vertex at the origin (0, 0, 0, 0), signs ignored, rejects the triangle: every point
//   of the triangle is then a positive multiple of a point on the opposite edge, so its image
//   is that edge's, a line of no area (llvmpipe draws nothing either).
bool prepare_clip_input(const ClipVertex in[3], ClipVertex out[3]);

// 3 input vertices plus one per plane at most (clipping a convex polygon against one plane
// adds at most one vertex).
inline constexpr int kMaxClippedVertices = 9;

struct ClipPlanes {
  float guard_x;  // |x| <= guard_x w keeps the window x inside the guard band
  float guard_y;
};

// A vertex of a clipped polygon: homogeneous clip coordinates in double, and which input
// vertex it is.
struct PolygonVertex {
  double x, y, z, w;
  int source;  // 0..2: input vertex `source`, unchanged; -1: a vertex made by clipping
};

enum class ClipOutcome { kInside, kOutside, kClipped };

// Zero or a normal finite float: neither the all-ones exponent (infinity, NaN) nor a zero
// exponent with a non-zero fraction (a denormal). Tested on the bits.
inline bool ordinary_clip_coordinate(float c) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(c);
  const std::uint32_t exponent = (bits >> 23) & 0xffu;
  return exponent != 0xffu && (exponent != 0u || (bits & 0x7fffffu) == 0u);
}

// A vertex that prepare_clip_input passes through unchanged whatever the other two are: four
// ordinary coordinates, not all zero. A triangle of three such vertices is prepared as itself.
inline bool plain_clip_vertex(const ClipVertex& v) {
  return ordinary_clip_coordinate(v.x) && ordinary_clip_coordinate(v.y) &&
         ordinary_clip_coordinate(v.z) && ordinary_clip_coordinate(v.w) &&
         !(v.x == 0.0f && v.y == 0.0f && v.z == 0.0f && v.w == 0.0f);
}

// Bit p set when vertex v is outside plane p (0 near, 1 far, 2 right, 3 left, 4 top,
// 5 bottom): what clip_triangle classifies a prepared triangle's vertices by (0 for all
// three: kInside; a bit common to all three: kOutside). NaN distances count as outside.
inline constexpr unsigned kClipOutcodeMask = 0x3fu;
inline unsigned clip_outcode(const ClipVertex& v, const ClipPlanes& planes) {
  const double gx = planes.guard_x, gy = planes.guard_y;
  const double x = v.x, y = v.y, z = v.z, w = v.w;
  const double gxw = gx * w, gyw = gy * w;
  return unsigned(!(w - z >= 0.0)) << 0 | unsigned(!(z >= 0.0)) << 1 |
         unsigned(!(gxw - x >= 0.0)) << 2 | unsigned(!(gxw + x >= 0.0)) << 3 |
         unsigned(!(gyw - y >= 0.0)) << 4 | unsigned(!(gyw + y >= 0.0)) << 5;
}

// Classifies the triangle (precondition: prepared by prepare_clip_input; other input is safe
// but NaN coordinates count as outside). kInside: count = 3, `out` unused. kOutside: count = 0.
// kClipped: `out` holds the convex polygon in the input's winding, count vertices (0 when
// nothing is left), each with w > 0.
ClipOutcome clip_triangle(const ClipVertex in[3], const ClipPlanes& planes,
                          PolygonVertex out[kMaxClippedVertices], int& count);

}  // namespace relief::raster
