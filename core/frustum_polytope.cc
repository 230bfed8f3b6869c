#include "core/frustum_polytope.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

// Inside tests accept this much (relative to the magnitudes involved) outside a plane: a
// crossing point computed in double lies on its plane within a few ulps (1e-16 relative).
constexpr double kInsideTolerance = 1e-9;

// How far p lies outside the plane, against the tolerance: > 0 outside.
double outside(const glm::dvec4& plane, const glm::dvec3& p) {
  const glm::dvec3 n(plane);
  // |n| (|x| + |y| + |z|) >= |n| |p|: a tolerance at least as large as the relative one.
  const double scale =
      glm::length(n) * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z)) + std::abs(plane.w);
  return glm::dot(n, p) - plane.w - kInsideTolerance * scale;
}

bool inside(const ConvexPolytope& poly, const glm::dvec3& p) {
  for (const glm::dvec4& plane : poly.planes) {
    if (outside(plane, p) > 0.0) {
      return false;
    }
  }
  return true;
}

}  // namespace

bool separated(const ConvexPolytope& a, const ConvexPolytope& b) {
  if (b.vertices.empty()) {
    return false;  // unbounded (a slab): not decided here
  }
  for (const glm::dvec4& plane : a.planes) {
    bool all_outside = true;
    for (const glm::dvec3& v : b.vertices) {
      if (!(outside(plane, v) > 0.0)) {
        all_outside = false;
        break;
      }
    }
    if (all_outside) {
      return true;
    }
  }
  return false;
}

bool contains(const ConvexPolytope& a, const ConvexPolytope& b) {
  return !b.vertices.empty() && std::all_of(b.vertices.begin(), b.vertices.end(),
                                            [&](const glm::dvec3& v) { return inside(a, v); });
}

namespace {

// Where the edges of `a` cross the face planes of `b`, kept when inside `b` (they lie on a's
// edges, so inside `a`).
void append_crossings(const ConvexPolytope& a, const ConvexPolytope& b,
                      std::vector<glm::dvec3>& out) {
  for (const auto& edge : a.edges) {
    const glm::dvec3& p = a.vertices[static_cast<std::size_t>(edge[0])];
    const glm::dvec3& q = a.vertices[static_cast<std::size_t>(edge[1])];
    for (const glm::dvec4& plane : b.planes) {
      const glm::dvec3 n(plane);
      const double sp = glm::dot(n, p) - plane.w;
      const double sq = glm::dot(n, q) - plane.w;
      // Strict crossing: an end point on the plane is a vertex, tested on its own. Division
      // domain: the signs differ, so sp - sq != 0.
      if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
        const glm::dvec3 x = p + (sp / (sp - sq)) * (q - p);
        if (inside(b, x)) {
          out.push_back(x);
        }
      }
    }
  }
}

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

ConvexPolytope frustum_polytope(const CameraFrame& camera) {
  ConvexPolytope f;
  // Corners in the order near (bl, br, tr, tl), far (bl, br, tr, tl).
  const double distances[2] = {camera.near, camera.far};
  const double sx[4] = {-1, 1, 1, -1};
  const double sy[4] = {-1, -1, 1, 1};
  for (const double d : distances) {
    for (int c = 0; c < 4; ++c) {
      f.vertices.push_back(d * (camera.forward + sx[c] * camera.tan_half_fov_x * camera.right +
                                sy[c] * camera.tan_half_fov_y * camera.up));
    }
  }
  f.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
             {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  const glm::dvec3& fw = camera.forward;
  f.planes = {glm::dvec4(-fw, -camera.near), glm::dvec4(fw, camera.far),
              // Side planes through the camera: right . p <= tan_x forward . p, and so on.
              glm::dvec4(camera.right - camera.tan_half_fov_x * fw, 0.0),
              glm::dvec4(-camera.right - camera.tan_half_fov_x * fw, 0.0),
              glm::dvec4(camera.up - camera.tan_half_fov_y * fw, 0.0),
              glm::dvec4(-camera.up - camera.tan_half_fov_y * fw, 0.0)};
  return f;
}

ConvexPolytope slab_polytope(double y_lo, double y_hi) {
  ConvexPolytope s;
  s.planes = {glm::dvec4(0.0, -1.0, 0.0, -y_lo), glm::dvec4(0.0, 1.0, 0.0, y_hi)};
  return s;
}

ConvexPolytope prism_polytope(const std::array<glm::dvec2, 4>& quad, double y_lo, double y_hi) {
  ConvexPolytope p;
  for (const double y : {y_lo, y_hi}) {
    for (const glm::dvec2& c : quad) {
      p.vertices.emplace_back(c.x, y, c.y);
    }
  }
  p.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
             {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  p.planes = {glm::dvec4(0.0, -1.0, 0.0, -y_lo), glm::dvec4(0.0, 1.0, 0.0, y_hi)};
  const glm::dvec2 centre = 0.25 * (quad[0] + quad[1] + quad[2] + quad[3]);
  for (int k = 0; k < 4; ++k) {
    const glm::dvec2& a = quad[static_cast<std::size_t>(k)];
    const glm::dvec2 e = quad[static_cast<std::size_t>((k + 1) % 4)] - a;
    glm::dvec3 n(e.y, 0.0, -e.x);  // perpendicular to the side, either way
    if (n.x * (centre.x - a.x) + n.z * (centre.y - a.y) > 0.0) {
      n = -n;  // outward: the centre is inside
    }
    p.planes.emplace_back(n, n.x * a.x + n.z * a.y);
  }
  return p;
}

void append_intersection_vertices(const ConvexPolytope& a, const ConvexPolytope& b,
                                  std::vector<glm::dvec3>& out) {
  // Two shortcuts, each exact: a separating face plane leaves nothing, and a bounded b inside
  // a is its own intersection.
  if (separated(a, b) || separated(b, a)) {
    return;
  }
  if (contains(a, b)) {
    out.insert(out.end(), b.vertices.begin(), b.vertices.end());
    return;
  }
  for (const glm::dvec3& v : a.vertices) {
    if (inside(b, v)) {
      out.push_back(v);
    }
  }
  for (const glm::dvec3& v : b.vertices) {
    if (inside(a, v)) {
      out.push_back(v);
    }
  }
  append_crossings(a, b, out);
  append_crossings(b, a, out);
}

std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points) {
  // Akl and Toussaint's filter: the points extreme in x, y, x + y and x - y span a polygon
  // inside the hull, and a point strictly inside it is on no hull edge. Dropping those first
  // leaves the sort a few points out of thousands (the refined polytope's vertices).
  if (points.size() > 64) {
    const auto extreme = [&](auto key) {
      return *std::min_element(
          points.begin(), points.end(),
          [&](const glm::dvec2& p, const glm::dvec2& q) { return key(p) < key(q); });
    };
    // Counter-clockwise: lowest y, lowest x - y... around.
    std::vector<glm::dvec2> ring = {extreme([](const glm::dvec2& p) { return p.y; }),
                                    extreme([](const glm::dvec2& p) { return -(p.x - p.y); }),
                                    extreme([](const glm::dvec2& p) { return -p.x; }),
                                    extreme([](const glm::dvec2& p) { return -(p.x + p.y); }),
                                    extreme([](const glm::dvec2& p) { return -p.y; }),
                                    extreme([](const glm::dvec2& p) { return p.x - p.y; }),
                                    extreme([](const glm::dvec2& p) { return p.x; }),
                                    extreme([](const glm::dvec2& p) { return p.x + p.y; })};
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    const auto strictly_inside = [&](const glm::dvec2& p) {
      for (std::size_t k = 0; k < ring.size(); ++k) {
        if (!(cross(ring[k], ring[(k + 1) % ring.size()], p) > 0.0)) {
          return false;
        }
      }
      return true;
    };
    if (ring.size() >= 3) {
      points.erase(std::remove_if(points.begin(), points.end(), strictly_inside), points.end());
    }
  }
  std::sort(points.begin(), points.end(), [](const glm::dvec2& p, const glm::dvec2& q) {
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) {
    return points;
  }
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const glm::dvec2& p : points) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) {
      --k;
    }
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) {
      --k;
    }
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

bool hull_span(const std::vector<glm::dvec2>& hull, double y, double& x_lo, double& x_hi) {
  bool found = false;
  x_lo = 1e300;
  x_hi = -1e300;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const glm::dvec2& a = hull[k];
    const glm::dvec2& b = hull[(k + 1) % hull.size()];
    if (y < std::min(a.y, b.y) || y > std::max(a.y, b.y)) {
      continue;
    }
    found = true;
    if (a.y == b.y) {  // a horizontal edge at y: both ends
      x_lo = std::min({x_lo, a.x, b.x});
      x_hi = std::max({x_hi, a.x, b.x});
      continue;
    }
    // Division domain: a.y != b.y. t in [0, 1] since y lies between them.
    const double x = a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
    x_lo = std::min(x_lo, x);
    x_hi = std::max(x_hi, x);
  }
  return found;
}

bool hull_span_between(const std::vector<glm::dvec2>& hull, double y_lo, double y_hi, double& x_lo,
                       double& x_hi) {
  x_lo = 1e300;
  x_hi = -1e300;
  bool found = false;
  for (const double y : {y_lo, y_hi}) {
    double a, b;
    if (hull_span(hull, y, a, b)) {
      found = true;
      x_lo = std::min(x_lo, a);
      x_hi = std::max(x_hi, b);
    }
  }
  for (const glm::dvec2& p : hull) {
    if (p.y >= y_lo && p.y <= y_hi) {
      found = true;
      x_lo = std::min(x_lo, p.x);
      x_hi = std::max(x_hi, p.x);
    }
  }
  return found;
}

}  // namespace relief
