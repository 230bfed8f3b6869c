// Helpers of the planet tests (tests/core/planet_geometry_test.cc,
// tests/pipeline/planet_frame_test.cc): the planet preset at a chosen altitude on a
// small grid, and the camera-relative position of a vertex, bent or planar.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/grid_buffers.h"
#include "core/scene/scene_json.h"

namespace relief::test {

// The planet preset (R = 2e6, base height 100) with the camera `altitude` above the datum,
// grid and viewport small, and `extra` overrides after them.
inline Scene planet_scene(double altitude, std::vector<std::string> extra = {}, int grid = 64) {
  std::vector<std::string> overrides = {
      "camera.position=[0, " + std::to_string(100.0 + altitude) + ", 0]",
      "grid.width=" + std::to_string(grid), "grid.height=" + std::to_string(grid),
      "viewport.width=96", "viewport.height=72"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return resolve_scene("planet", overrides);
}

struct Position {
  double x = 0, y = 0, z = 0;
  double length() const { return std::sqrt(x * x + y * y + z * z); }
};

// Vertex k's camera-relative position: bent on a planet, (dx, height, dz) on the plane.
template <class Real>
Position vertex_position(const GridBuffers<Real>& g, std::size_t k) {
  if (!g.bent_x.empty()) {
    return {double(g.bent_x[k]), double(g.bent_y[k]), double(g.bent_z[k])};
  }
  return {double(g.dx[k]), double(g.height[k]), double(g.dz[k])};
}

}  // namespace relief::test
