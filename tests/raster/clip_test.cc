// Clipping without OpenGL: for any finite input no vertex with w <= 0 or a non-finite window
// coordinate reaches snapping, degenerate vertices draw nothing, and clipped triangles cover
// the exact image of the triangle (long double, tests/oracles/clip_reference.h) up to snapping,
// with depth and barycentrics within the bounds of docs/rasteriser-accuracy.md.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "raster/clip.h"
#include "raster/rasterize.h"
#include "raster/triangle_setup.h"
#include "tests/oracles/clip_accuracy.h"
#include "tests/oracles/clip_reference.h"

namespace relief::raster {
namespace {

using test::Exact;
using test::hashed_uniform;

// One coordinate of the hostile input set: zeros of both signs, denormals, magnitudes from
// 1e-38 to 1e30 of either sign, the soup reader's limit, the largest floats, ordinary values.
float hostile_coordinate(std::uint64_t key) {
  const double kind = hashed_uniform(key, 0, 1);
  const double sign = hashed_uniform(key + 1, 0, 1) < 0.5 ? -1.0 : 1.0;
  if (kind < 0.1) {
    return float(sign * 0.0);
  }
  if (kind < 0.2) {
    return float(sign * std::pow(10.0, hashed_uniform(key + 2, -45, -38)));  // denormal
  }
  if (kind < 0.22) {
    return float(sign * 1e30);  // the soup reader's limit
  }
  if (kind < 0.25) {
    return float(sign * 3.4e38);  // near the largest float
  }
  if (kind < 0.6) {
    return float(sign * std::pow(10.0, hashed_uniform(key + 2, -38, 30)));
  }
  return float(hashed_uniform(key + 2, -2, 2));
}

ClipVertex hostile_vertex(std::uint64_t key) {
  ClipVertex v{hostile_coordinate(key), hostile_coordinate(key + 5), hostile_coordinate(key + 10),
               hostile_coordinate(key + 15)};
  const double shape = hashed_uniform(key + 20, 0, 1);
  if (shape < 0.05) {
    v = {0.0f, 0.0f, 0.0f, 0.0f};
  } else if (shape < 0.15) {
    v.z = v.w;  // on the near plane
  } else if (shape < 0.25) {
    v.w = 0.0f;  // a point at infinity
  } else if (shape < 0.3) {
    v.z = 0.0f;  // on the far plane
  }
  return v;
}

RasterState state_for(int width, int height, const Viewport& viewport) {
  RasterState state;
  state.width = width;
  state.height = height;
  state.viewport = viewport;
  state.depth_test = DepthTest::kAlways;
  return state;
}

TEST_CASE("clippingNeverYieldsANonPositiveWOrANonFiniteWindowCoordinate", "[raster]") {
  const RasterState states[2] = {state_for(64, 48, {0, 0, 64, 48}),
                                 state_for(64, 48, {32 - 8192, 24 - 8192, 16384, 16384})};
  int clipped = 0, pieces = 0;
  for (const RasterState& state : states) {
    const TriangleSetup setup(state);
    const ClipPlanes planes{
        float((kGuardBandPixels - std::abs(state.viewport.x + state.viewport.width / 2)) /
              (state.viewport.width / 2)),
        float((kGuardBandPixels - std::abs(state.viewport.y + state.viewport.height / 2)) /
              (state.viewport.height / 2))};
    for (std::uint64_t k = 0; k < 20000; ++k) {
      const ClipVertex input[3] = {hostile_vertex(k * 100), hostile_vertex(k * 100 + 30),
                                   hostile_vertex(k * 100 + 60)};
      ClipVertex v[3];
      if (prepare_clip_input(input, v)) {
        PolygonVertex polygon[kMaxClippedVertices];
        int count = -1;
        if (clip_triangle(v, planes, polygon, count) == ClipOutcome::kClipped) {
          ++clipped;
          REQUIRE(count >= 0);
          REQUIRE(count <= kMaxClippedVertices);
          for (int i = 0; i < count; ++i) {
            REQUIRE(polygon[i].w > 0.0);
            double x = 0, y = 0;
            setup.to_window(polygon[i], x, y);
            INFO("triangle " << k << " vertex " << i << ": window (" << x << ", " << y << ")");
            REQUIRE(std::abs(x) <= kGuardBandPixels + 1);
            REQUIRE(std::abs(y) <= kGuardBandPixels + 1);
          }
        }
      }
      std::vector<RasterTriangle> out;
      setup.setup_clip(static_cast<std::uint32_t>(k), input, out);
      for (const RasterTriangle& t : out) {
        ++pieces;
        REQUIRE(t.x0 >= 0);
        REQUIRE(t.x1 < state.width);
        REQUIRE(t.y0 >= 0);
        REQUIRE(t.y1 < state.height);
        REQUIRE(std::isfinite(t.z0));
        REQUIRE(std::isfinite(t.dzdx));
        REQUIRE(std::isfinite(t.dzdy));
        // depth() clamps to GL's depth range, so only a NaN (an infinite plane coefficient
        // times a zero) could leave it; a range check would say no more than this.
        REQUIRE_FALSE(std::isnan(t.depth(t.x0, t.y0)));
      }
    }
  }
  CHECK(clipped > 5000);  // the set exercises the clipper, not just the trivial cases
  CHECK(pieces > 1000);

  // The whole pipeline (binning, tiles, per-pixel depth) on the same set, under the sanitizers.
  std::vector<float> x, y, z, w;
  std::vector<std::uint32_t> indices;
  for (std::uint64_t k = 0; k < 3 * 20000; ++k) {
    const ClipVertex v = hostile_vertex((k / 3) * 100 + (k % 3) * 30);
    x.push_back(v.x), y.push_back(v.y), z.push_back(v.z), w.push_back(v.w);
    indices.push_back(static_cast<std::uint32_t>(k));
  }
  VisibilityBuffer b;
  rasterize(states[0], ClipVertices{x, y, z, w}, IndexedTriangles{indices}, b);
  // Depths are written clamped to [0, 1] (RasterTriangle::depth): only a NaN could get through.
  CHECK(std::none_of(b.depth.begin(), b.depth.end(), [](float d) { return std::isnan(d); }));
}

TEST_CASE("meshesCutByTheNearPlaneCoverEveryPixelOnce", "[raster]") {
  // A 12 x 10 grid of vertices around the framebuffer, each with w log-uniform in [1e-3, 1e9]
  // and a depth z/w from 0.2 to 1.6: the near plane (z/w = 1) cuts many triangles along a
  // line that is continuous across shared edges. Neighbours share their new vertices bit for
  // bit, so no pixel may be covered twice, and every pixel of the visible part (z/w <= 1)
  // farther than the tolerance from the cut must be covered once.
  const RasterState state = test::set_state();
  const Viewport& vp = state.viewport;
  // sx, sy > 0 (a viewport has a size): divided by below.
  const double sx = vp.width / 2, sy = vp.height / 2, tx = vp.x + sx, ty = vp.y + sy;
  constexpr int kColumns = 12, kRows = 10;
  std::vector<ClipVertex> grid;
  for (int j = 0; j < kRows; ++j) {
    for (int i = 0; i < kColumns; ++i) {
      const std::uint64_t key = 5000000 + static_cast<std::uint64_t>(j * kColumns + i) * 8;
      const double px = -20 + 12.0 * i + hashed_uniform(key, -3, 3);
      const double py = -20 + 13.0 * j + hashed_uniform(key + 1, -3, 3);
      const double wv = std::pow(10.0, hashed_uniform(key + 2, -3, 9));
      const double depth = hashed_uniform(key + 3, 0.2, 1.6);
      grid.push_back(
          {float((px - tx) / sx * wv), float((py - ty) / sy * wv), float(depth * wv), float(wv)});
    }
  }
  const TriangleSetup setup(state);
  std::vector<int> count(test::kSetWidth * test::kSetHeight, 0);
  // Per pixel: how far (px) it lies inside the visible part, from the exact depth of the
  // unclipped triangle containing it; all vertices have w > 0, so that triangle is the 2D one
  // through the vertices' window positions, and z/w is affine over it.
  std::vector<Exact> visible(count.size(), -1);
  int clipped_triangles = 0;
  for (int j = 0; j + 1 < kRows; ++j) {
    for (int i = 0; i + 1 < kColumns; ++i) {
      const ClipVertex a = grid[j * kColumns + i], b = grid[j * kColumns + i + 1];
      const ClipVertex c = grid[(j + 1) * kColumns + i + 1], d = grid[(j + 1) * kColumns + i];
      const ClipVertex triangles[2][3] = {{a, b, c}, {a, c, d}};
      for (const auto& t : triangles) {
        clipped_triangles += (t[0].z > t[0].w) || (t[1].z > t[1].w) || (t[2].z > t[2].w);
        std::vector<RasterTriangle> pieces;
        setup.setup_clip(0, t, pieces);
        for (const RasterTriangle& piece : pieces) {
          for_each_covered_pixel(piece,
                                 [&](int px, int py) { ++count[py * test::kSetWidth + px]; });
        }
        ClipVertex unclipped[3];  // the same rays, moved in front of the near plane
        for (int k = 0; k < 3; ++k) {
          unclipped[k] = {t[k].x, t[k].y, 0.0f, t[k].w};
        }
        const test::ExactTriangle whole(unclipped, vp);
        for (int py = 0; py < test::kSetHeight; ++py) {
          for (int px = 0; px < test::kSetWidth; ++px) {
            const Exact u = px + Exact(0.5), v = py + Exact(0.5);
            Exact bc[3], ignored;
            if (!(whole.signed_distance(u, v) <= 0) || !whole.interpolate(u, v, bc, ignored)) {
              continue;
            }
            auto depth = [&](Exact uu, Exact vv) {  // domain: every w > 0, so the sum is too
              Exact bb[3] = {0, 0, 0};
              whole.interpolate(uu, vv, bb, ignored);
              return (bb[0] * t[0].z + bb[1] * t[1].z + bb[2] * t[2].z) /
                     (bb[0] * t[0].w + bb[1] * t[1].w + bb[2] * t[2].w);
            };
            const Exact h = 1e-3L;
            const Exact gx = (depth(u + h, v) - depth(u - h, v)) / (2 * h);
            const Exact gy = (depth(u, v + h) - depth(u, v - h)) / (2 * h);
            // Domain: the gradient is finite; where it is zero the cut is infinitely far.
            const Exact gradient = std::sqrt(gx * gx + gy * gy);
            const Exact margin = (1 - depth(u, v)) / std::max(gradient, Exact(1e-30L));
            visible[py * test::kSetWidth + px] = margin;
          }
        }
      }
    }
  }
  int covered = 0, missing = 0, twice = 0, extra = 0;
  for (std::size_t k = 0; k < count.size(); ++k) {
    covered += count[k] == 1;
    twice += count[k] > 1;
    missing += count[k] == 0 && visible[k] > test::kCoverageTolerance;
    extra += count[k] > 0 && visible[k] < -test::kCoverageTolerance;
  }
  INFO(clipped_triangles << " of 198 triangles cross the near plane; " << covered
                         << " pixels covered once");
  CHECK(clipped_triangles > 40);
  CHECK(covered > 1000);
  CHECK(twice == 0);
  CHECK(missing == 0);
  CHECK(extra == 0);
}

TEST_CASE("degenerateVerticesDrawOnlyWhatTheExactTriangleCovers", "[raster]") {
  // Each case: a hostile third vertex with two ordinary ones in front of the near plane.
  REQUIRE(static_cast<float>(1e-300) == 0.0f);  // what the soup reader makes of 1e-300
  const Viewport viewport{0, 0, 64, 64};
  const RasterState state = state_for(64, 64, viewport);
  int drawn = 0;
  for (const ClipVertex& hostile : test::hostile_vertices()) {
    for (int rotation = 0; rotation < 3; ++rotation) {
      ClipVertex v[3] = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {-0.5f, 0.75f, 0.25f, 1}};
      v[rotation] = hostile;
      const test::ClipCoverage c = test::compare_with_exact(state, v);
      INFO("vertex (" << hostile.x << ", " << hostile.y << ", " << hostile.z << ", " << hostile.w
                      << ") at " << rotation << ": " << c.covered << " pixels, exact "
                      << c.exact_covered << ", worst mismatch " << c.worst_mismatch_distance);
      CHECK(c.mismatches_beyond_tolerance == 0);
      if (c.exact_empty) {
        CHECK(c.covered == 0);
      }
      drawn += c.covered > 0;
    }
  }
  CHECK(drawn > 20);
}

TEST_CASE("aTriangleWithWOverThirteenDecadesCoversItsExactImage", "[raster]") {
  // The soup of the issue that found the clipper dropping triangles (and the third triangle of
  // docs/soups/clip.txt): 256 x 256, viewport = framebuffer, w from 0.81 to 6.8e12.
  const ClipVertex v[3] = {{float(-0.2334834074465895), float(-0.8683522811054649),
                            float(0.16182116720835496), float(0.8138562466273351)},
                           {float(-18734.875945198884), float(47545.95096789103),
                            float(53560.03768413838), float(31137.11241636935)},
                           {float(2137011401661.0479), float(-2647202640354.418),
                            float(5258390561894.958), float(6751986602280.072)}};
  const test::ClipCoverage c = test::compare_with_exact(state_for(256, 256, {0, 0, 256, 256}), v);
  CHECK(c.exact_covered == 9251);
  CHECK(c.covered == 9251);
  CHECK(c.mismatches == 0);
}

TEST_CASE("nearPlaneCrossingTrianglesCoverTheirExactImageUpToSnapping", "[raster]") {
  const test::AccuracySet set = test::near_plane_set();
  const test::AccuracyStats s = test::measure_relief(set);
  INFO(s.summary());
  CHECK(s.triangles == set.count);
  CHECK(s.covered > 100000);
  CHECK(s.mismatches_beyond_tolerance == 0);
  CHECK(s.worst_depth_error <= test::kDepthBound);
  CHECK(s.worst_barycentric_error <= test::kBarycentricBound);
}

TEST_CASE("unclippedTrianglesHaveDepthAndBarycentricsWithinTheSameBound", "[raster]") {
  const test::AccuracySet set = test::unclipped_set();
  const test::AccuracyStats s = test::measure_relief(set);
  INFO(s.summary());
  CHECK(s.covered > 100000);
  CHECK(s.mismatches_beyond_tolerance == 0);
  CHECK(s.worst_depth_error <= test::kDepthBound);
  CHECK(s.worst_barycentric_error <= test::kBarycentricBound);
}

}  // namespace
}  // namespace relief::raster
