// Stage 2, per-frame part: the projector frustum and range mapping of the projected grid
// (§4.1, Figure 5; Johanson 2004, "Real-time water rendering: the projected grid concept").
//
// Terrain can only be seen where the camera frustum (near to far plane) meets the slab of
// possible heights [world_min, world_max] (height_bounds.h). That intersection is a convex
// polytope; its vertices are the frustum corners inside the slab and the crossings of the
// frustum's edges with the slab's two planes. Their vertical projections span every base-domain
// point whose terrain could appear on screen.
//
// The projector is a pinhole at the camera position, without roll, looking down at a
// horizontal "projection plane" below it. The plane's height only parametrises the grid, so it
// is placed at the base height when the camera is above it: the projector then sees the
// terrain the way the camera does. The pitch bisects the depression angles of the projected
// polytope vertices, so all of them are in front of it (|angle off axis| < 90 degrees). The
// bounding box of their projector-image coordinates is the coverage box; since the projected
// polytope is convex and the projector is a projective map, the box covers all of it.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/height_bounds.h"

namespace relief {

struct ImageBox {
  double x0 = 0, x1 = 0;  // projector-image coordinates: x right, y up, focal length 1
  double y0 = 0, y1 = 0;
};

struct Projector {
  bool terrain_visible = false;  // false: the frustum misses the slab, nothing to draw
  glm::dvec3 forward{0, -1, 0};  // projector axes, world orientation
  glm::dvec3 right{1, 0, 0};
  glm::dvec3 up{0, 0, -1};
  double height_above_plane = 1;      // camera height above the projection plane, > 0
  ImageBox coverage;                  // covers every footprint that can be seen
  double max_footprint_distance = 0;  // kMaxFootprintFactor x the farthest footprint
};

// Vertices of (frustum between near and far plane) intersected with the slab
// y_lo <= y <= y_hi; positions relative to the camera, slab heights relative to the camera.
std::vector<glm::dvec3> frustum_slab_vertices(const CameraFrame& camera, double y_lo, double y_hi);

Projector make_projector(const CameraFrame& camera, const HeightBounds& bounds, double base_height);

// The footprint of the projector ray through image point (x, y) on the projection plane, as
// camera-relative (dx, dz). `descent` is the ray's downward component -ray.y for that image
// row, from projector_descent(): near the horizon ray.y = y cos(pitch) - sin(pitch) cancels
// almost completely, so it is formed once per row in double instead of per vertex in Real
// (in float the per-vertex form put footprints 1 unit off at 100 km; this form, 0.03).
// Returns false (and leaves dx, dz at 0) where the ray does not descend (at or above the
// horizon) or lands beyond max_footprint_distance. The same arithmetic serves float and
// double; the operation order is the specification.
template <class Real>
struct ProjectorRays {
  Real fx, fz;  // horizontal components of forward,
  Real rx, rz;  // right (horizontal: the projector has no roll)
  Real ux, uz;  // and up
  Real height_above_plane;
  Real max_distance_sq;

  explicit ProjectorRays(const Projector& p)
      : fx(Real(p.forward.x)),
        fz(Real(p.forward.z)),
        rx(Real(p.right.x)),
        rz(Real(p.right.z)),
        ux(Real(p.up.x)),
        uz(Real(p.up.z)),
        height_above_plane(Real(p.height_above_plane)),
        max_distance_sq(Real(p.max_footprint_distance * p.max_footprint_distance)) {}

  bool footprint(Real x, Real y, Real descent, Real& dx, Real& dz) const;
};

// -ray.y of the projector ray through image row y: cos(pitch) (tan(pitch) - y), in double.
inline double projector_descent(const Projector& p, double y) {
  return -(p.forward.y + y * p.up.y);
}

}  // namespace relief
