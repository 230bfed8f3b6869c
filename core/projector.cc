#include "core/projector.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/limits.h"

namespace relief {

std::vector<glm::dvec3> frustum_slab_vertices(const CameraFrame& camera, double y_lo, double y_hi) {
  // Corners in the order near (bl, br, tr, tl), far (bl, br, tr, tl).
  std::array<glm::dvec3, 8> corners;
  const double distances[2] = {camera.near, camera.far};
  for (int plane = 0; plane < 2; ++plane) {
    const double d = distances[plane];
    const double sx[4] = {-1, 1, 1, -1};
    const double sy[4] = {-1, -1, 1, 1};
    for (int c = 0; c < 4; ++c) {
      corners[plane * 4 + c] = d * (camera.forward + sx[c] * camera.tan_half_fov_x * camera.right +
                                    sy[c] * camera.tan_half_fov_y * camera.up);
    }
  }
  constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                 {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::vector<glm::dvec3> vertices;
  for (const glm::dvec3& corner : corners) {
    if (corner.y >= y_lo && corner.y <= y_hi) {
      vertices.push_back(corner);
    }
  }
  for (const auto& edge : kEdges) {
    const glm::dvec3& a = corners[edge[0]];
    const glm::dvec3& b = corners[edge[1]];
    for (double plane_y : {y_lo, y_hi}) {
      // Strict crossing: a corner on the plane is already in the list. Division domain:
      // the signs differ, so a.y != b.y.
      if ((a.y - plane_y) * (b.y - plane_y) < 0.0) {
        const double t = (plane_y - a.y) / (b.y - a.y);
        glm::dvec3 p = a + t * (b - a);
        p.y = plane_y;
        vertices.push_back(p);
      }
    }
  }
  return vertices;
}

Projector make_projector(const CameraFrame& camera, const HeightBounds& bounds,
                         double base_height) {
  Projector projector;
  const double y_lo = bounds.world_min - camera.position.y;
  const double y_hi = bounds.world_max - camera.position.y;
  const std::vector<glm::dvec3> vertices = frustum_slab_vertices(camera, y_lo, y_hi);
  if (vertices.empty()) {
    return projector;
  }
  // The projection plane: at the base height when the camera is above it, else just below the
  // camera. Its height is a parametrisation of the grid only (see the header).
  const double clearance = std::max(camera.near, 0.01 * (bounds.world_max - bounds.world_min));
  const double plane_y = std::min(base_height - camera.position.y, -clearance);
  projector.height_above_plane = -plane_y;

  // Horizontal forward: the camera's right is horizontal for every pitch, so this is defined
  // looking straight down too.
  const glm::dvec3 world_up(0, 1, 0);
  const glm::dvec3 horizontal_forward = glm::cross(world_up, camera.right);
  double theta_min = M_PI;
  double theta_max = 0.0;
  double farthest_sq = 0.0;
  for (const glm::dvec3& v : vertices) {
    const double ahead = glm::dot(v, horizontal_forward);
    const double theta = std::atan2(projector.height_above_plane, ahead);  // in (0, pi)
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

  ImageBox box{1e300, -1e300, 1e300, -1e300};
  for (const glm::dvec3& v : vertices) {
    const glm::dvec3 foot(v.x, plane_y, v.z);
    // Domain: |theta - pitch| < pi/2 for every vertex, so depth > 0 (bounded away from 0 by
    // the finite far plane and clearance).
    const double depth = glm::dot(foot, projector.forward);
    const double x = glm::dot(foot, projector.right) / depth;
    const double y = glm::dot(foot, projector.up) / depth;
    box.x0 = std::min(box.x0, x);
    box.x1 = std::max(box.x1, x);
    box.y0 = std::min(box.y0, y);
    box.y1 = std::max(box.y1, y);
  }
  // Widen the box by a relative 1e-9 (and to at least a sliver): points on the polytope's
  // boundary land exactly on the box edge, and rounding must not push them outside.
  constexpr double kRelativeWidening = 1e-9;
  constexpr double kMinHalfExtent = 1e-9;
  const double grow_x = std::max(kRelativeWidening * (box.x1 - box.x0), kMinHalfExtent);
  const double grow_y = std::max(kRelativeWidening * (box.y1 - box.y0), kMinHalfExtent);
  box.x0 -= grow_x;
  box.x1 += grow_x;
  box.y0 -= grow_y;
  box.y1 += grow_y;
  projector.coverage = box;
  projector.max_footprint_distance = limits::kMaxFootprintFactor * std::sqrt(farthest_sq);
  projector.terrain_visible = true;
  return projector;
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
