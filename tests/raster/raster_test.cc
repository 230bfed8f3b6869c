// The rasteriser's rules, checked without OpenGL: snapping, fill rule, culling, depth test
// order, clipping, determinism, and the resolve's perspective-correct attributes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include "raster/rasterize.h"
#include "raster/resolve.h"
#include "raster/triangle_setup.h"
#include "tests/support/test_support.h"

namespace relief::raster {
namespace {

RasterState state_for(int width, int height) {
  RasterState state;
  state.width = width;
  state.height = height;
  state.viewport = {0, 0, double(width), double(height)};
  return state;
}

// Window-coordinate triangles, 3 vertices each, drawn with the window path.
struct WindowSoup {
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> indices;
  void add(float x0, float y0, float x1, float y1, float x2, float y2, float depth) {
    for (auto [vx, vy] : {std::pair{x0, y0}, {x1, y1}, {x2, y2}}) {
      indices.push_back(static_cast<std::uint32_t>(x.size()));
      x.push_back(vx);
      y.push_back(vy);
      z.push_back(depth);
    }
  }
  VisibilityBuffer draw(const RasterState& state) const {
    VisibilityBuffer out;
    rasterize(state, WindowVertices{x, y, z}, IndexedTriangles{indices}, out);
    return out;
  }
};

std::vector<std::pair<int, int>> covered(const VisibilityBuffer& b, std::uint32_t primitive) {
  std::vector<std::pair<int, int>> pixels;
  for (int py = 0; py < b.height; ++py) {
    for (int px = 0; px < b.width; ++px) {
      if (b.primitive[b.index(px, py)] == primitive) {
        pixels.emplace_back(px, py);
      }
    }
  }
  return pixels;
}

TEST_CASE("snappingRoundsToTheNearestSubpixelTiesToEven", "[raster]") {
  // Fixed frame: pixel centres at multiples of 256, i.e. X = (x - 0.5) * 256.
  CHECK(snap_to_fixed(0.5f) == 0);
  CHECK(snap_to_fixed(1.5f) == 256);
  CHECK(snap_to_fixed(0.5f + 1.0f / 256) == 1);
  CHECK(snap_to_fixed(0.5f + 0.5f / 256) == 0);   // tie: to even (0)
  CHECK(snap_to_fixed(0.5f + 1.5f / 256) == 2);   // tie: to even (2)
  CHECK(snap_to_fixed(0.5f - 0.5f / 256) == 0);   // tie: to even (0)
  CHECK(snap_to_fixed(0.5f - 1.5f / 256) == -2);  // tie: to even (-2)
}

TEST_CASE("rasterCoversPixelCentresOnLeftAndBottomEdgesOnly", "[raster]") {
  // A 4 x 4 px square with its sides exactly through pixel centres: x from 2.5 to 6.5,
  // y from 1.5 to 5.5. Left (x = 2.5) and bottom (y = 1.5) centres belong to it, right
  // (x = 6.5) and top (y = 5.5) ones do not: 4 x 4 pixels, (2..5, 1..4).
  for (bool clockwise : {false, true}) {
    WindowSoup soup;
    if (clockwise) {
      soup.add(2.5f, 1.5f, 6.5f, 5.5f, 6.5f, 1.5f, 0.5f);
      soup.add(2.5f, 1.5f, 2.5f, 5.5f, 6.5f, 5.5f, 0.5f);
    } else {
      soup.add(2.5f, 1.5f, 6.5f, 1.5f, 6.5f, 5.5f, 0.5f);
      soup.add(2.5f, 1.5f, 6.5f, 5.5f, 2.5f, 5.5f, 0.5f);
    }
    const VisibilityBuffer b = soup.draw(state_for(10, 8));
    int count = 0;
    for (int py = 0; py < 8; ++py) {
      for (int px = 0; px < 10; ++px) {
        const bool inside = px >= 2 && px <= 5 && py >= 1 && py <= 4;
        CHECK((b.primitive[b.index(px, py)] != kNoPrimitive) == inside);
        count += b.primitive[b.index(px, py)] != kNoPrimitive;
      }
    }
    CHECK(count == 16);
  }
}

TEST_CASE("rasterCoversASharedEdgeOnce", "[raster]") {
  // Two triangles sharing a diagonal through pixel centres: each centre on the diagonal goes
  // to exactly one of them.
  const RasterState state = state_for(16, 16);
  const TriangleSetup setup(state);
  std::vector<RasterTriangle> pieces;
  const float x0[3] = {0.5f, 12.5f, 12.5f}, y0[3] = {0.5f, 0.5f, 12.5f}, z[3] = {0.5f, 0.5f, 0.5f};
  const float x1[3] = {0.5f, 12.5f, 0.5f}, y1[3] = {0.5f, 12.5f, 12.5f};
  setup.setup_window(0, x0, y0, z, pieces);
  setup.setup_window(1, x1, y1, z, pieces);
  REQUIRE(pieces.size() == 2);
  // The diagonal's centres (the top-right corner (12, 12) belongs to the quad's neighbours
  // to the right and above: it lies on this quad's right and top edges).
  for (int k = 0; k < 12; ++k) {
    CHECK(pieces[0].covers(k, k) + pieces[1].covers(k, k) == 1);
  }
  CHECK(pieces[0].covers(12, 12) + pieces[1].covers(12, 12) == 0);
}

TEST_CASE("rasterCullsByWindingAndDropsZeroArea", "[raster]") {
  WindowSoup soup;
  soup.add(1, 1, 9, 1, 1, 9, 0.5f);  // counter-clockwise: front with GL's default
  soup.add(1, 1, 1, 9, 9, 1, 0.5f);  // the same, clockwise
  soup.add(1, 1, 5, 5, 9, 9, 0.5f);  // collinear
  RasterState state = state_for(12, 12);
  state.depth_test = DepthTest::kAlways;
  state.cull = CullMode::kBack;
  CHECK(!covered(soup.draw(state), 0).empty());
  CHECK(covered(soup.draw(state), 1).empty());
  state.cull = CullMode::kFront;
  CHECK(covered(soup.draw(state), 0).empty());
  CHECK(!covered(soup.draw(state), 1).empty());
  state.front_face = FrontFace::kClockwise;
  CHECK(!covered(soup.draw(state), 0).empty());
  state.cull = CullMode::kNone;
  CHECK(covered(soup.draw(state), 2).empty());
}

TEST_CASE("depthTestKeepsTheFirstOfEqualDepthsUnderGreater", "[raster]") {
  WindowSoup soup;
  soup.add(0, 0, 8, 0, 0, 8, 0.5f);
  soup.add(0, 0, 8, 0, 0, 8, 0.5f);
  soup.add(0, 0, 8, 0, 0, 8, 0.25f);  // farther under reverse-Z
  RasterState state = state_for(8, 8);
  const VisibilityBuffer greater = soup.draw(state);
  CHECK(covered(greater, 0).size() > 10);
  CHECK(covered(greater, 1).empty());
  state.depth_test = DepthTest::kGreaterEqual;  // equal passes: the later one wins
  CHECK(covered(soup.draw(state), 1).size() == covered(greater, 0).size());
  state.depth_test = DepthTest::kLess;
  state.depth_clear = 1.0f;
  CHECK(covered(soup.draw(state), 2).size() == covered(greater, 0).size());
}

TEST_CASE("rasterDrawsOnlyInsideViewportAndFramebuffer", "[raster]") {
  WindowSoup soup;
  soup.add(-100, -100, 300, -100, -100, 300, 0.5f);
  RasterState state = state_for(20, 10);
  state.viewport = {4, 2, 8, 5};
  const auto pixels = covered(soup.draw(state), 0);
  CHECK(pixels.size() == 8 * 5);
  for (auto [px, py] : pixels) {
    CHECK(px >= 4);
    CHECK(px < 12);
    CHECK(py >= 2);
    CHECK(py < 7);
  }
}

// A perspective camera looking along -z at a plane; clip coordinates of world points.
struct PerspectiveScene {
  double f = 1.0 / std::tan(M_PI / 6);  // 60 degree field of view, square viewport
  double near = 0.1;
  ClipVertex clip(double x, double y, double z) const {
    return {float(x * f), float(y * f), float(near), float(-z)};
  }
};

TEST_CASE("clippedTrianglesCoverExactlyTheVisiblePart", "[raster]") {
  // A ground triangle running from behind the camera to far ahead: its part in front of the
  // near plane must be drawn, with nothing outside it. A pixel is inside iff its
  // perspective-correct barycentrics are all positive (checked away from the edges).
  const PerspectiveScene cam;
  const ClipVertex v[3] = {cam.clip(-3, -1, 5), cam.clip(3, -1, 5), cam.clip(0, -1, -60)};
  std::vector<float> x, y, z, w;
  for (const ClipVertex& c : v) {
    x.push_back(c.x), y.push_back(c.y), z.push_back(c.z), w.push_back(c.w);
  }
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  RasterState state = state_for(64, 64);
  VisibilityBuffer b;
  const RasterStats stats =
      rasterize(state, ClipVertices{x, y, z, w}, IndexedTriangles{indices}, b);
  CHECK(stats.setup >= 1);
  const double xs[3] = {x[0] * 32.0 + w[0] * 32.0, x[1] * 32.0 + w[1] * 32.0,
                        x[2] * 32.0 + w[2] * 32.0};
  const double ys[3] = {y[0] * 32.0 + w[0] * 32.0, y[1] * 32.0 + w[1] * 32.0,
                        y[2] * 32.0 + w[2] * 32.0};
  const double ws[3] = {w[0], w[1], w[2]};
  const PerspectivePlane plane(xs, ys, ws);
  int inside = 0;
  for (int py = 0; py < 64; ++py) {
    for (int px = 0; px < 64; ++px) {
      double bc[3];
      REQUIRE(plane.barycentrics(px + 0.5, py + 0.5, bc));
      const double margin = std::min({bc[0], bc[1], bc[2]});
      const bool drawn = b.primitive[b.index(px, py)] == 0;
      // Depth along the ray: points in front of the near plane have w > near.
      const double wp = bc[0] * ws[0] + bc[1] * ws[1] + bc[2] * ws[2];
      if (margin > 1e-3 && wp > cam.near * 1.001) {
        CHECK(drawn);
        ++inside;
      }
      if (margin < -1e-3 || wp < cam.near * 0.999) {
        CHECK_FALSE(drawn);
      }
    }
  }
  CHECK(inside > 500);
}

TEST_CASE("resolveInterpolatesPerspectiveCorrectlyWithQuadDerivatives", "[raster]") {
  // A tilted plane in front of the camera; attribute = world x of each vertex. The resolved
  // value at a pixel must be the x of the point the pixel's ray hits, and the derivatives the
  // fine (2 x 2 quad) differences of that same function.
  const PerspectiveScene cam;
  const double world[4][3] = {{-4, -2, -3}, {4, -2, -3}, {4, 3, -12}, {-4, 3, -12}};
  std::vector<float> x, y, z, w, attribute;
  for (const auto& p : world) {
    const ClipVertex c = cam.clip(p[0], p[1], p[2]);
    x.push_back(c.x), y.push_back(c.y), z.push_back(c.z), w.push_back(c.w);
    attribute.push_back(float(p[0]));
  }
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const RasterState state = state_for(48, 48);
  const ClipVertices clip{x, y, z, w};
  VisibilityBuffer b;
  rasterize(state, clip, IndexedTriangles{indices}, b);
  ResolvedFrame frame;
  const std::span<const float> streams[1] = {attribute};
  resolve(b, VertexPositions::from_clip(clip, state.viewport), IndexedTriangles{indices},
          std::span<const std::span<const float>>(streams), 1, frame);
  // Ray through pixel centre (u, v) meets the plane through the quad: x(u, v) in closed form.
  const glm::dvec3 p0(world[0][0], world[0][1], world[0][2]);
  const glm::dvec3 normal =
      glm::normalize(glm::cross(glm::dvec3(world[1][0], world[1][1], world[1][2]) - p0,
                                glm::dvec3(world[3][0], world[3][1], world[3][2]) - p0));
  auto world_x = [&](double u, double v) {
    const glm::dvec3 ray((2 * u / 48 - 1) / cam.f, (2 * v / 48 - 1) / cam.f, -1);
    return (glm::dot(p0, normal) / glm::dot(ray, normal)) * ray.x;
  };
  int checked = 0;
  for (int py = 0; py < 48; ++py) {
    for (int px = 0; px < 48; ++px) {
      const std::size_t k = b.index(px, py);
      if (b.primitive[k] == kNoPrimitive) {
        continue;
      }
      ++checked;
      const double u = px + 0.5, v = py + 0.5;
      CHECK(frame.value[0][k] == Approx(world_x(u, v)).margin(1e-4));
      const double left = (px & 1) ? u - 1 : u, bottom = (py & 1) ? v - 1 : v;
      CHECK(frame.ddx[0][k] == Approx(world_x(left + 1, v) - world_x(left, v)).margin(1e-4));
      CHECK(frame.ddy[0][k] == Approx(world_x(u, bottom + 1) - world_x(u, bottom)).margin(1e-4));
      CHECK(frame.b0[k] + frame.b1[k] + frame.b2[k] == Approx(1.0).margin(1e-5));
    }
  }
  CHECK(checked > 300);
}

TEST_CASE("visibilityBufferIsIdenticalForEveryThreadCount", "[raster]") {
  test::TestRandom random(17);
  WindowSoup soup;
  for (int k = 0; k < 3000; ++k) {
    const float cx = float(random.uniform(-20, 340)), cy = float(random.uniform(-20, 260));
    soup.add(cx, cy, cx + float(random.uniform(-30, 30)), cy + float(random.uniform(-30, 30)),
             cx + float(random.uniform(-30, 30)), cy + float(random.uniform(-30, 30)),
             float(random.uniform(0, 1)));
  }
  const RasterState state = state_for(320, 240);
  const VisibilityBuffer reference = [&] {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    return soup.draw(state);
  }();
  for (int threads : {2, 3, 8}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const VisibilityBuffer b = soup.draw(state);
    CHECK(b.primitive == reference.primitive);
    CHECK(std::memcmp(b.depth.data(), reference.depth.data(), b.depth.size() * 4) == 0);
  }
}

}  // namespace
}  // namespace relief::raster
