// Stage 2, per-frame part: the projector frustum and range mapping of the projected grid
// (§4.1, Figure 5; Johanson 2004, "Real-time water rendering: the projected grid concept").
//
// Terrain can only be seen where the camera frustum (near to far plane) meets the slab of
// possible heights [world_min, world_max] (height_bounds.h). That intersection is a convex
// polytope; its vertices are the frustum corners inside the slab and the crossings of the
// frustum's edges with the slab's two planes. Their vertical projections span every base-domain
// point whose terrain could appear on screen.
//
// The slab is the terrain's global height range, about three times the relief near any one
// place, and it usually contains the camera: the polytope then reaches from the near plane
// under the camera, and half the grid used to cover ground below the bottom of the screen. So
// the polytope is refined per region (docs/paper-reading.md, "§4.1: the projector"): the
// projector image of the global polytope is cut into kRefineCells^2 cells, each the image of a
// convex quadrilateral of the base plane; over each, the terrain lies within its regional
// height bound [L, U] (height_bound_pyramid.h), so every visible terrain point there lies in
// frustum ∩ (quad x [L, U]), a convex polytope. The cells tile the image, so every visible
// terrain point lies in one of these pieces (Figure 5's requirement), and the pieces' vertices
// take the place of the global polytope's below. Pieces a regional bound keeps out of the
// frustum (ground under the camera whose terrain cannot reach the lowest rays) contribute
// nothing.
//
// The projector is a pinhole at the camera position, without roll, looking down at a
// horizontal "projection plane" below it. The plane's height only parametrises the grid, so it
// is placed at the base height when the camera is above it: the projector then sees the
// terrain the way the camera does. The pitch bisects the depression angles of the projected
// polytope vertices, so all of them are in front of it (|angle off axis| < 90 degrees). The
// convex hull of their projector-image coordinates is the coverage hull, and its bounding box
// the coverage box; since each piece is convex and the projector is a projective map, the hull
// covers every piece's image. Stage 1 spans each grid row over the hull's extent between its
// neighbouring rows (screen_grid.h), so few columns land left or right of what can be seen.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/height_bounds.h"
#include "core/parallel_rows.h"
#include "core/stage_param_fields.h"

namespace relief {

struct TerrainPlan;  // frame_plan.h, which includes this header

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
  std::vector<glm::dvec2> hull;       // and so does this convex polygon (counter-clockwise)
  double max_footprint_distance = 0;  // kMaxFootprintFactor x the farthest footprint
};

// Cells per side of the projector-image tiling the polytope is refined over (header), and the
// passes: the second tiles the first's coverage, finer where it matters. Two passes of 24^2
// cells take 2 ms a frame on one thread (rows of cells run through ParallelRows) and set up
// 46% of the default frame's triangles; one pass of 32^2,
// 46%; 64^2 cells, about 49% for 20 ms.
inline constexpr int kRefineCells = 24;
inline constexpr int kRefinePasses = 2;

// Vertices of (frustum between near and far plane) intersected with the slab
// y_lo <= y <= y_hi; positions relative to the camera, slab heights relative to the camera.
std::vector<glm::dvec3> frustum_slab_vertices(const CameraFrame& camera, double y_lo, double y_hi);

// `terrain`: refine the polytope by the regional height bound of this terrain (header); null
// takes the global slab alone. The refinement's rows of cells run through `parallel`; their
// vertices are joined in row order, so the projector is the same bits however they ran.
Projector make_projector(const CameraFrame& camera, const HeightBounds& bounds, double base_height,
                         const TerrainPlan* terrain = nullptr, const ParallelRows& parallel = {});

// make_projector's last step: the projector fitted to camera-relative points (its pitch
// bisects their footprints' depression angles), the projection plane `height_above_plane`
// (> 0) below the camera. A planet frame adds points of its own (planet_plan.h).
Projector fit_projector_to_points(const CameraFrame& camera, const std::vector<glm::dvec3>& points,
                                  double height_above_plane);

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
  RELIEF_DECLARE_FIELDS(RELIEF_PROJECTOR_RAYS_FIELDS)

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
