// What the accuracy tests measure (docs/rasteriser-accuracy.md): Relief's coverage, depth and
// barycentrics against the exact image of each triangle (tests/oracles/clip_reference.h), one
// triangle at a time, on the randomised sets shared by the GL-free and GL tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "raster/rasterize.h"
#include "raster/resolve.h"
#include "raster/triangle_setup.h"
#include "tests/oracles/clip_reference.h"

namespace relief::test {

// A pixel may be drawn differently from the exact triangle only where its centre lies within
// this distance of the exact image's boundary: snapping moves every vertex by at most 1/512
// px in x and y, so every snapped edge lies within sqrt(2)/512 px (0.0028) of the exact one;
// the float window coordinates of input vertices (as GL computes them) add under 1e-4 px
// within a few hundred pixels of the origin, where the sets place them.
inline constexpr double kCoverageTolerance = 1.0 / 256;

// Depth against exact arithmetic, at pixel centres the exact triangle covers (clamped to
// [0, 1] like GL's): clipped or not, Relief takes the plane of the whole triangle from its clip
// coordinates in double, and rounds once to float: within one float ulp of 1 (measured: half
// an ulp, docs/rasteriser-accuracy.md).
inline constexpr double kDepthBound = 0x1.0p-24;

// Perspective-correct barycentrics (raster/resolve.h, from the original triangle in double,
// rounded to float) against exact arithmetic: within one float ulp of 1 (measured: half).
inline constexpr double kBarycentricBound = 0x1.0p-24;

// The framebuffer and viewport of the sets: the GL cross-check's, whose 16384-px viewport
// centred on a 96 x 80 framebuffer keeps llvmpipe from clipping at the framebuffer's edge, or
// a viewport equal to the framebuffer, where it does.
inline constexpr int kSetWidth = 96;
inline constexpr int kSetHeight = 80;

struct AccuracySet {
  raster::RasterState state;
  std::vector<raster::ClipVertex> vertices;  // 3 per triangle
  int count = 0;
};

inline raster::RasterState set_state(bool viewport_is_framebuffer = false) {
  raster::RasterState state;
  state.width = kSetWidth;
  state.height = kSetHeight;
  state.viewport = {kSetWidth / 2.0 - 8192, kSetHeight / 2.0 - 8192, 16384, 16384};
  if (viewport_is_framebuffer) {
    state.viewport = {0, 0, kSetWidth, kSetHeight};
  }
  state.depth_test = raster::DepthTest::kAlways;
  return state;
}

// Triangles crossing the near plane, |w| log-uniform in [1e-6, 1e13] (near_plane_triangle).
inline AccuracySet near_plane_set(int count = 400, bool viewport_is_framebuffer = false) {
  AccuracySet set{set_state(viewport_is_framebuffer), {}, count};
  for (int k = 0; k < count; ++k) {
    raster::ClipVertex v[3];
    near_plane_triangle(static_cast<std::uint64_t>(k), kSetWidth, kSetHeight, set.state.viewport,
                        v);
    set.vertices.insert(set.vertices.end(), v, v + 3);
  }
  return set;
}

// Triangles in front of the near plane and inside the guard band (never clipped), with
// non-dyadic window coordinates and depths, and w log-uniform in [1e-3, 1e3] per vertex.
// Hostile vertices for the degenerate-vertex tests: the origin (signed zeros and denormals
// included: flushed, as GL does), w = 0 and w = +-denormal, the soup reader's 1e-300, the
// soup's 1e30 limit, a vertex behind the eye, and tiny but normal coordinates.
inline std::vector<raster::ClipVertex> hostile_vertices() {
  const float denormal = 1e-45f;
  const float from_soup = static_cast<float>(1e-300);  // what the soup reader makes of 1e-300
  return {
      {0, 0, 0, 0},
      {-0.0f, 0, -0.0f, -0.0f},
      {0, 2.5e-39f, 2.5e-39f, 5e-39f},  // a valid point in denormals: the origin once flushed
      {0, 0.5f, 0.5f, 0},               // w = 0 behind the near plane: a point at infinity
      {0, 0.5f, 0, 0},                  // w = 0 on the near and far planes
      {0, 0.5f, 0, -0.0f},
      {0.25f, 0.5f, 0.5f, denormal},
      {0.25f, 0.5f, 0.5f, -denormal},
      {0.25f, -0.5f, 0.25f, from_soup},
      {0.25f, -0.5f, 0.25f, -from_soup},
      {denormal, denormal, denormal, denormal},
      {-denormal, 0, denormal, -denormal},
      {0, 1e30f, 1e30f, 1e30f},  // on the near plane at the soup's limit
      {1e30f, -1e30f, 0.5e30f, 1e30f},
      {-1e30f, 0, 1e30f, -1e30f},  // behind the eye
      {1e-30f, 0, 0.5e-30f, 1e-30f},
  };
}

inline AccuracySet unclipped_set(int count = 300) {
  AccuracySet set{set_state(), {}, count};
  const raster::Viewport& vp = set.state.viewport;
  // sx, sy > 0 (a viewport has a size): divided by below.
  const double sx = vp.width / 2, sy = vp.height / 2, tx = vp.x + sx, ty = vp.y + sy;
  for (int k = 0; k < count; ++k) {
    const std::uint64_t key = 1000000 + static_cast<std::uint64_t>(k) * 64;
    const double cx = hashed_uniform(key, 0, kSetWidth),
                 cy = hashed_uniform(key + 1, 0, kSetHeight);
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t vk = key + 8 * (i + 1);
      const double w = std::pow(10.0, hashed_uniform(vk, -3, 3));
      const double px = cx + hashed_uniform(vk + 1, -60, 60);
      const double py = cy + hashed_uniform(vk + 2, -60, 60);
      const double depth = hashed_uniform(vk + 3, 0.001, 0.999);
      set.vertices.push_back(
          {float((px - tx) / sx * w), float((py - ty) / sy * w), float(depth * w), float(w)});
    }
  }
  return set;
}

struct ClipCoverage {
  int covered = 0;
  int exact_covered = 0;
  bool exact_empty = true;
  int mismatches = 0;
  int mismatches_beyond_tolerance = 0;
  double worst_mismatch_distance = 0;  // px from the exact boundary
};

struct AccuracyStats {
  int triangles = 0;
  long covered = 0;
  long mismatches = 0;
  long mismatches_beyond_tolerance = 0;
  double worst_mismatch_distance = 0;
  double worst_depth_error = 0;
  double worst_barycentric_error = 0;

  std::string summary() const {
    std::ostringstream s;
    s << triangles << " triangles, " << covered << " pixels covered, " << mismatches
      << " differ from the exact image (" << mismatches_beyond_tolerance
      << " beyond the tolerance; farthest " << worst_mismatch_distance
      << " px from its boundary); depth error " << worst_depth_error << ", barycentric error "
      << worst_barycentric_error;
    return s.str();
  }
};

// Relief's pixels for one clip-space triangle: depth per pixel, NaN where uncovered.
inline std::vector<float> relief_pixels(const raster::RasterState& state,
                                        const raster::ClipVertex v[3]) {
  std::vector<float> depth(static_cast<std::size_t>(state.width) * state.height, NAN);
  const raster::TriangleSetup setup(state);
  std::vector<raster::RasterTriangle> pieces;
  setup.setup_clip(0, v, pieces);
  for (const raster::RasterTriangle& t : pieces) {
    raster::for_each_covered_pixel(t, [&](int px, int py) {
      depth[static_cast<std::size_t>(py) * state.width + px] = t.depth(px, py);
    });
  }
  return depth;
}

// Per pixel: Relief's coverage against the exact image, and (accumulated into `stats` when
// given) depth and barycentric errors where both cover the pixel.
inline ClipCoverage compare_with_exact(const raster::RasterState& state,
                                       const raster::ClipVertex v[3],
                                       AccuracyStats* stats = nullptr) {
  const ExactTriangle exact(v, state.viewport);
  const std::vector<float> depth = relief_pixels(state, v);
  std::vector<float> x, y, z, w;
  for (int k = 0; k < 3; ++k) {
    x.push_back(v[k].x), y.push_back(v[k].y), z.push_back(v[k].z), w.push_back(v[k].w);
  }
  const raster::VertexPositions positions =
      raster::VertexPositions::from_clip(raster::ClipVertices{x, y, z, w}, state.viewport);
  double hx[3], hy[3], hw[3];
  for (std::uint32_t k = 0; k < 3; ++k) {
    positions.get(k, hx[k], hy[k], hw[k]);
  }
  const raster::PerspectivePlane plane(hx, hy, hw);
  ClipCoverage c;
  c.exact_empty = exact.empty();
  for (int py = 0; py < state.height; ++py) {
    for (int px = 0; px < state.width; ++px) {
      const Exact u = px + Exact(0.5), vv = py + Exact(0.5);
      const Exact distance = exact.signed_distance(u, vv);
      const float d = depth[static_cast<std::size_t>(py) * state.width + px];
      const bool ours = !std::isnan(d);
      const bool theirs = distance < 0;
      c.covered += ours;
      c.exact_covered += theirs;
      if (ours != theirs) {
        ++c.mismatches;
        c.worst_mismatch_distance = std::max(c.worst_mismatch_distance, double(std::abs(distance)));
        c.mismatches_beyond_tolerance += std::abs(distance) > kCoverageTolerance;
        continue;
      }
      Exact b[3], exact_depth;
      if (!stats || !ours || !exact.interpolate(u, vv, b, exact_depth)) {
        continue;
      }
      stats->worst_depth_error =
          std::max(stats->worst_depth_error, double(std::abs(d - exact_depth)));
      double relief_b[3];
      if (plane.barycentrics(px + 0.5, py + 0.5, relief_b)) {
        for (int i = 0; i < 3; ++i) {
          const double error = std::abs(float(relief_b[i]) - b[i]);  // resolve stores floats
          stats->worst_barycentric_error = std::max(stats->worst_barycentric_error, error);
        }
      }
    }
  }
  return c;
}

inline AccuracyStats measure_relief(const AccuracySet& set) {
  AccuracyStats s;
  for (int k = 0; k < set.count; ++k) {
    const ClipCoverage c = compare_with_exact(set.state, &set.vertices[3 * k], &s);
    ++s.triangles;
    s.covered += c.covered;
    s.mismatches += c.mismatches;
    s.mismatches_beyond_tolerance += c.mismatches_beyond_tolerance;
    s.worst_mismatch_distance = std::max(s.worst_mismatch_distance, c.worst_mismatch_distance);
  }
  return s;
}

}  // namespace relief::test
