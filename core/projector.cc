#include "core/projector.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/frame_plan.h"
#include "core/frustum_polytope.h"
#include "core/height_bound_pyramid.h"
#include "core/limits.h"

namespace relief {

std::vector<glm::dvec3> frustum_slab_vertices(const CameraFrame& camera, double y_lo, double y_hi) {
  std::vector<glm::dvec3> vertices;
  append_intersection_vertices(frustum_polytope(camera), slab_polytope(y_lo, y_hi), vertices);
  return vertices;
}

namespace {

// Widen the coverage by a relative 1e-9 (and to at least a sliver): points on a piece's
// boundary land exactly on the hull's edge, and rounding must not push them outside.
constexpr double kRelativeWidening = 1e-9;
constexpr double kMinHalfExtent = 1e-9;

// Image point of a camera-relative point's footprint on the projection plane. Domain: the
// footprint is within 90 degrees of the projector's axis (fit_projector's pitch bisects the
// depression angles of every point it is fitted to), so depth > 0.
glm::dvec2 image_of(const Projector& p, const glm::dvec3& v) {
  const glm::dvec3 foot(v.x, -p.height_above_plane, v.z);
  const double depth = glm::dot(foot, p.forward);
  return {glm::dot(foot, p.right) / depth, glm::dot(foot, p.up) / depth};
}

// The projector axes, coverage and farthest footprint for a set of camera-relative points (the
// polytope's vertices): the pitch bisects their footprints' depression angles.
Projector fit_projector(const CameraFrame& camera, const std::vector<glm::dvec3>& vertices,
                        double height_above_plane) {
  Projector projector;
  projector.height_above_plane = height_above_plane;
  // Horizontal forward: the camera's right is horizontal for every pitch, so this is defined
  // looking straight down too.
  const glm::dvec3 world_up(0, 1, 0);
  const glm::dvec3 horizontal_forward = glm::cross(world_up, camera.right);
  double theta_min = M_PI;
  double theta_max = 0.0;
  double farthest_sq = 0.0;
  for (const glm::dvec3& v : vertices) {
    const double ahead = glm::dot(v, horizontal_forward);
    const double theta = std::atan2(height_above_plane, ahead);  // in (0, pi)
    theta_min = std::min(theta_min, theta);
    theta_max = std::max(theta_max, theta);
    farthest_sq = std::max(farthest_sq, v.x * v.x + v.z * v.z);
  }
  const double pitch_down = 0.5 * (theta_min + theta_max);  // depression of the axis
  const double c = std::cos(pitch_down);
  const double s = std::sin(pitch_down);
  projector.forward = c * horizontal_forward - s * world_up;
  projector.up = s * horizontal_forward + c * world_up;
  projector.right = camera.right;  // forward x up, as for the camera

  std::vector<glm::dvec2> images;
  images.reserve(vertices.size());
  ImageBox box{1e300, -1e300, 1e300, -1e300};
  for (const glm::dvec3& v : vertices) {
    const glm::dvec2 q = image_of(projector, v);
    images.push_back(q);
    box.x0 = std::min(box.x0, q.x);
    box.x1 = std::max(box.x1, q.x);
    box.y0 = std::min(box.y0, q.y);
    box.y1 = std::max(box.y1, q.y);
  }
  const double grow_x = std::max(kRelativeWidening * (box.x1 - box.x0), kMinHalfExtent);
  const double grow_y = std::max(kRelativeWidening * (box.y1 - box.y0), kMinHalfExtent);
  // The hull grows with the box: the hull of its vertices moved to the four corners of the
  // widening (the Minkowski sum with it) contains the hull of the points, and is never a point
  // or a segment.
  const std::vector<glm::dvec2> hull = convex_hull(std::move(images));
  std::vector<glm::dvec2> widened;
  widened.reserve(4 * hull.size());
  for (const glm::dvec2& q : hull) {
    for (const double sx : {-grow_x, grow_x}) {
      for (const double sy : {-grow_y, grow_y}) {
        widened.emplace_back(q.x + sx, q.y + sy);
      }
    }
  }
  box.x0 -= grow_x;
  box.x1 += grow_x;
  box.y0 -= grow_y;
  box.y1 += grow_y;
  projector.coverage = box;
  projector.hull = convex_hull(std::move(widened));
  projector.max_footprint_distance = limits::kMaxFootprintFactor * std::sqrt(farthest_sq);
  projector.terrain_visible = true;
  return projector;
}

// The vertices of the refined polytope (projector.h): the global projector's coverage box cut
// into kRefineCells^2 image cells, each the image of a quadrilateral of the projection plane,
// intersected with the frustum between that quadrilateral's regional height bounds. False when
// some cell corner's ray does not descend clearly (a coverage box touching the horizon): the
// caller keeps the global polytope.
bool refined_vertices(const CameraFrame& camera, const Projector& global,
                      const RegionalHeightBound& regional, const ParallelRows& parallel,
                      std::vector<glm::dvec3>& out) {
  const ImageBox& box = global.coverage;
  constexpr int n = kRefineCells;
  // Footprints of the cell corners on the projection plane, camera-relative (x, z).
  std::vector<glm::dvec2> foot(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int b = 0; b <= n; ++b) {
    for (int a = 0; a <= n; ++a) {
      const double x = box.x0 + (box.x1 - box.x0) * a / n;
      const double y = box.y0 + (box.y1 - box.y0) * b / n;
      const glm::dvec3 ray = global.forward + x * global.right + y * global.up;
      // Domain of the division: the ray descends by at least 1e-12 of its length.
      if (!(-ray.y > 1e-12 * glm::length(ray))) {
        return false;
      }
      const double t = global.height_above_plane / -ray.y;
      foot[static_cast<std::size_t>(b * (n + 1) + a)] = {t * ray.x, t * ray.z};
    }
  }
  const ConvexPolytope frustum = frustum_polytope(camera);
  const ValueRange slab = regional.global();
  // Each row of cells appends to its own list (read-only inputs: foot, frustum, regional).
  std::vector<std::vector<glm::dvec3>> rows(static_cast<std::size_t>(n));
  const auto row_cells = [&](int b) {
    std::vector<glm::dvec3>& row = rows[static_cast<std::size_t>(b)];
    for (int a = 0; a < n; ++a) {
      const auto at = [&](int i, int j) { return foot[static_cast<std::size_t>(j * (n + 1) + i)]; };
      const std::array<glm::dvec2, 4> quad = {at(a, b), at(a + 1, b), at(a + 1, b + 1),
                                              at(a, b + 1)};
      double x0 = quad[0].x, x1 = quad[0].x, z0 = quad[0].y, z1 = quad[0].y;
      for (const glm::dvec2& q : quad) {
        x0 = std::min(x0, q.x);
        x1 = std::max(x1, q.x);
        z0 = std::min(z0, q.y);
        z1 = std::max(z1, q.y);
      }
      // Neighbouring quads share their corners exactly; the bound's box is widened like the
      // coverage, so a point on a shared side is inside both boxes whatever the rounding.
      const double grow = kRelativeWidening * std::max({x1 - x0, z1 - z0, std::abs(x0),
                                                        std::abs(x1), std::abs(z0), std::abs(z1)});
      // Two shortcuts before the regional bound: a quadrilateral whose prism through the
      // whole slab misses the frustum contributes nothing, and one whose prism lies inside it
      // contributes its corners (the projector reads footprints only) whatever its bound.
      const ConvexPolytope slab_prism = prism_polytope(quad, slab.lo, slab.hi);
      if (separated(frustum, slab_prism)) {
        continue;
      }
      if (contains(frustum, slab_prism)) {
        row.insert(row.end(), slab_prism.vertices.begin(), slab_prism.vertices.begin() + 4);
        continue;
      }
      const ValueRange h = regional.bound(x0 - grow, x1 + grow, z0 - grow, z1 + grow);
      append_intersection_vertices(frustum, prism_polytope(quad, h.lo, h.hi), row);
    }
  };
  run_rows(parallel, n, row_cells);
  for (const std::vector<glm::dvec3>& row : rows) {  // row order: the serial loop's
    out.insert(out.end(), row.begin(), row.end());
  }
  return true;
}

}  // namespace

Projector make_projector(const CameraFrame& camera, const HeightBounds& bounds, double base_height,
                         const TerrainPlan* terrain, const ParallelRows& parallel) {
  const double y_lo = bounds.world_min - camera.position.y;
  const double y_hi = bounds.world_max - camera.position.y;
  const std::vector<glm::dvec3> vertices = frustum_slab_vertices(camera, y_lo, y_hi);
  if (vertices.empty()) {
    return Projector{};
  }
  // The projection plane: at the base height when the camera is above it, else just below the
  // camera. Its height is a parametrisation of the grid only (see the header).
  const double clearance = std::max(camera.near, 0.01 * (bounds.world_max - bounds.world_min));
  const double plane_y = std::min(base_height - camera.position.y, -clearance);
  const Projector global = fit_projector(camera, vertices, -plane_y);
  if (terrain == nullptr) {
    return global;
  }
  // Per frame: 0.08 ms at P = 256, 7 ms at P = 4096, where the scene's resources would be the
  // place to keep it.
  const LatticeRangePyramid pyramid = make_lattice_range_pyramid(*terrain->lattice);
  const RegionalHeightBound regional(*terrain, pyramid);
  Projector projector = global;
  for (int pass = 0; pass < kRefinePasses; ++pass) {
    std::vector<glm::dvec3> refined;
    if (!refined_vertices(camera, projector, regional, parallel, refined)) {
      return projector;
    }
    if (refined.empty()) {
      return Projector{};  // no region's terrain can reach the frustum
    }
    projector = fit_projector(camera, refined, -plane_y);
  }
  return projector;
}

Projector fit_projector_to_points(const CameraFrame& camera, const std::vector<glm::dvec3>& points,
                                  double height_above_plane) {
  return fit_projector(camera, points, height_above_plane);
}

template <class Real>
bool ProjectorRays<Real>::footprint(Real x, Real y, Real descent, Real& dx, Real& dz) const {
  // The projector has no roll: its right axis is horizontal, so x does not change ray.y.
  const Real ray_x = fx + x * rx + y * ux;
  const Real ray_z = fz + x * rz + y * uz;
  dx = Real(0);
  dz = Real(0);
  const Real horizontal_sq = ray_x * ray_x + ray_z * ray_z;
  // Domain of the division below: descent > 0, and descent^2 above kMinRayDescent^2 of the
  // ray's squared length, so the footprint stays finite.
  const Real min_descent = Real(limits::kMinRayDescent);
  if (!(descent > Real(0)) ||
      descent * descent <= min_descent * min_descent * (horizontal_sq + descent * descent)) {
    return false;
  }
  const Real scale = height_above_plane / descent;
  const Real px = scale * ray_x;
  const Real pz = scale * ray_z;
  if (!(px * px + pz * pz <= max_distance_sq)) {
    return false;
  }
  dx = px;
  dz = pz;
  return true;
}

template struct ProjectorRays<float>;
template struct ProjectorRays<double>;

}  // namespace relief
