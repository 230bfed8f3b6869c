// Convex polytopes of the projector (§4.1, Figure 5; projector.h): the view frustum, the slab
// of every height the terrain can take, the prism of one region's heights, the vertices of
// their intersections, and the convex hull of points in the projector's image. All in double,
// camera-relative, once per frame.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"

namespace relief {

// A bounded or unbounded convex polytope: its vertices, its edges (pairs of vertex indices)
// and its faces' planes (x, y, z: outward normal n; w: d), inside where dot(n, p) <= d.
struct ConvexPolytope {
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<int, 2>> edges;
  std::vector<glm::dvec4> planes;
};

// The view frustum between the near and the far plane, relative to the camera.
ConvexPolytope frustum_polytope(const CameraFrame& camera);

// y_lo <= y <= y_hi (camera-relative): two planes, no vertices.
ConvexPolytope slab_polytope(double y_lo, double y_hi);

// The vertical prism over a convex quadrilateral of the base plane, corners (x, z) in order
// (either orientation), between the heights y_lo <= y_hi.
ConvexPolytope prism_polytope(const std::array<glm::dvec2, 4>& quad, double y_lo, double y_hi);

// Whether every vertex of the bounded polytope b lies outside one face plane of a (beyond the
// tolerance below): then a ∩ b is empty. False for an unbounded b.
bool separated(const ConvexPolytope& a, const ConvexPolytope& b);

// Whether every vertex of the bounded polytope b lies inside a (within the tolerance below):
// then a ∩ b is b.
bool contains(const ConvexPolytope& a, const ConvexPolytope& b);

// Appends a set of points whose convex hull contains a ∩ b (for bounded a or b: its vertices).
// Every vertex of the intersection is a vertex of one polytope inside the other, or where an
// edge of one crosses a face plane of the other; those are the candidates, kept when inside
// both. The inside tests accept points up to a relative 1e-9 outside, so rounding can only add
// points next to the intersection, never drop one of its vertices.
void append_intersection_vertices(const ConvexPolytope& a, const ConvexPolytope& b,
                                  std::vector<glm::dvec3>& out);

// The convex hull of points, counter-clockwise, without repeated or collinear points
// (Andrew's monotone chain). One or two points come back as they are.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points);

// The cross-section of a convex polygon (convex_hull's output) at height y: [x_lo, x_hi].
// False when y is outside the polygon's y range.
bool hull_span(const std::vector<glm::dvec2>& hull, double y, double& x_lo, double& x_hi);

// The x extent of the polygon's part between the heights y_lo <= y_hi: the cross-sections at
// both ends and the polygon's vertices between them. False when the part is empty.
bool hull_span_between(const std::vector<glm::dvec2>& hull, double y_lo, double y_hi, double& x_lo,
                       double& x_hi);

}  // namespace relief
