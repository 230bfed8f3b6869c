// The software rasteriser against real OpenGL (Mesa's llvmpipe through EGL's surfaceless
// platform): coverage and the winning primitive must be identical pixel for pixel, and depths
// must agree within kDepthBound.
//
// Inputs are exact by construction, so that both pipelines see the same window coordinates:
// every coordinate is dyadic, the viewport is 16384 x 16384 centred on the framebuffer (the
// largest llvmpipe allows: it never clips against the framebuffer's edges in float, and
// x_window = x_ndc * 8192 + W/2 is exact), and triangles crossing the near plane have clip
// distances +1 and -1 (t = 1/2) and power-of-two w, so every clipped vertex is exact too.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/counter_hash.h"
#include "gpu/gl_rasterizer.h"
#include "gpu/headless_gl.h"
#include "raster/rasterize.h"
#include "raster/triangle_setup.h"
#include "tests/gl/gl_test_context.h"

namespace relief {
namespace {

constexpr int kWidth = 96;  // not a multiple of the tile size: partial tiles are exercised
constexpr int kHeight = 80;
constexpr int kViewportSide = 16384;
constexpr double kHalfViewport = kViewportSide / 2.0;
// llvmpipe evaluates the depth plane in float from the framebuffer origin; Relief in double,
// rounding once. Measured: at most one float ulp of 1 (6e-8); the bound allows four.
constexpr double kDepthBound = 4.0 * 0x1.0p-24;

gpu::HeadlessGl& gl() {
  return test::gl_context();
}

// A triangle soup in clip coordinates, built from window or clip coordinates.
struct Soup {
  std::vector<float> x, y, z, w;
  std::vector<std::uint32_t> indices;

  void vertex(double cx, double cy, double cz, double cw) {
    indices.push_back(static_cast<std::uint32_t>(x.size()));
    x.push_back(static_cast<float>(cx));
    y.push_back(static_cast<float>(cy));
    z.push_back(static_cast<float>(cz));
    w.push_back(static_cast<float>(cw));
    REQUIRE(double(x.back()) == cx);  // exact by construction
    REQUIRE(double(y.back()) == cy);
  }
  // Window coordinates (pixels, depth) as w = 1 clip coordinates through the centred viewport.
  void window_vertex(double wx, double wy, double depth) {
    vertex((wx - kWidth / 2.0) / kHalfViewport, (wy - kHeight / 2.0) / kHalfViewport, depth, 1.0);
  }
  void window_triangle(double x0, double y0, double x1, double y1, double x2, double y2,
                       double depth) {
    window_vertex(x0, y0, depth);
    window_vertex(x1, y1, depth);
    window_vertex(x2, y2, depth);
  }
  std::uint32_t count() const { return static_cast<std::uint32_t>(indices.size() / 3); }
};

struct DrawState {
  raster::CullMode cull = raster::CullMode::kNone;
  raster::FrontFace front = raster::FrontFace::kCounterClockwise;
};

raster::RasterState raster_state(const DrawState& s) {
  raster::RasterState state;
  state.width = kWidth;
  state.height = kHeight;
  state.viewport = {kWidth / 2.0 - kHalfViewport, kHeight / 2.0 - kHalfViewport,
                    double(kViewportSide), double(kViewportSide)};
  state.cull = s.cull;
  state.front_face = s.front;
  return state;
}

struct Comparison {
  int covered = 0;
  int id_mismatches = 0;
  double worst_depth = 0;
  std::string first_mismatch;
};

Comparison compare_with_gl(const Soup& soup, const DrawState& s = {}) {
  const raster::RasterState state = raster_state(s);
  raster::VisibilityBuffer ours;
  raster::rasterize(state, raster::ClipVertices{soup.x, soup.y, soup.z, soup.w},
                    raster::IndexedTriangles{soup.indices}, ours);
  gpu::GlDraw draw;
  draw.width = kWidth;
  draw.height = kHeight;
  draw.viewport[0] = kWidth / 2 - kViewportSide / 2;
  draw.viewport[1] = kHeight / 2 - kViewportSide / 2;
  draw.viewport[2] = draw.viewport[3] = kViewportSide;
  draw.x = soup.x;
  draw.y = soup.y;
  draw.z = soup.z;
  draw.w = soup.w;
  draw.indices = soup.indices;
  draw.cull = s.cull == raster::CullMode::kNone   ? gpu::GlCull::kNone
              : s.cull == raster::CullMode::kBack ? gpu::GlCull::kBack
                                                  : gpu::GlCull::kFront;
  draw.front_face_ccw = s.front == raster::FrontFace::kCounterClockwise;
  const gpu::GlImage theirs = gpu::draw_with_gl(gl(), draw);
  Comparison c;
  for (int py = 0; py < kHeight; ++py) {
    for (int px = 0; px < kWidth; ++px) {
      const std::size_t k = ours.index(px, py);
      const bool covered = ours.primitive[k] != raster::kNoPrimitive;
      c.covered += covered;
      if (ours.primitive[k] != theirs.primitive[k]) {
        if (c.id_mismatches++ == 0) {
          c.first_mismatch = "pixel (" + std::to_string(px) + ", " + std::to_string(py) +
                             "): Relief " + std::to_string(int(ours.primitive[k])) + ", GL " +
                             std::to_string(int(theirs.primitive[k]));
        }
      } else {
        c.worst_depth = std::max(c.worst_depth, std::abs(double(ours.depth[k]) - theirs.depth[k]));
      }
    }
  }
  return c;
}

void require_identical(const Soup& soup, const DrawState& s = {}) {
  const Comparison c = compare_with_gl(soup, s);
  INFO("renderer " << gl().renderer() << "; " << soup.count() << " triangles, " << c.covered
                   << " pixels covered, worst depth difference " << c.worst_depth << "; first "
                   << "mismatch: " << c.first_mismatch);
  CHECK(c.id_mismatches == 0);
  CHECK(c.worst_depth <= kDepthBound);
}

// A dyadic pseudo-random value in [lo, hi) with `bits` fractional bits.
double dyadic(std::uint64_t key, double lo, double hi, int bits) {
  const double unit = unit_open_interval(mix64(key + kGoldenGamma));
  const double scale = std::ldexp(1.0, bits);
  return std::floor((lo + unit * (hi - lo)) * scale) / scale;
}

TEST_CASE("glCrossCheckMeshesSharingEdgesAndVerticesAreWatertight", "[gl]") {
  // A jittered grid reaching past the framebuffer on every side, cells split along alternating
  // diagonals, every other triangle wound clockwise, plus a 16-triangle fan.
  Soup soup;
  constexpr int kColumns = 11, kRows = 10;
  auto grid_x = [&](int i, int j) { return -12.0 + 12.0 * i + dyadic(j * 97 + i, -3, 3, 6); };
  auto grid_y = [&](int i, int j) {
    return -12.0 + 11.0 * j + dyadic(j * 97 + i + 5000, -3, 3, 6);
  };
  for (int j = 0; j + 1 < kRows; ++j) {
    for (int i = 0; i + 1 < kColumns; ++i) {
      const double ax = grid_x(i, j), ay = grid_y(i, j), bx = grid_x(i + 1, j),
                   by = grid_y(i + 1, j);
      const double cx = grid_x(i + 1, j + 1), cy = grid_y(i + 1, j + 1);
      const double dx = grid_x(i, j + 1), dy = grid_y(i, j + 1);
      if ((i + j) % 2) {
        soup.window_triangle(ax, ay, bx, by, cx, cy, 0.5);
        soup.window_triangle(ax, ay, dx, dy, cx, cy, 0.5);  // clockwise
      } else {
        soup.window_triangle(ax, ay, bx, by, dx, dy, 0.5);
        soup.window_triangle(bx, by, dx, dy, cx, cy, 0.5);  // clockwise
      }
    }
  }
  require_identical(soup);

  // Independent of GL: every framebuffer pixel lies inside the mesh and must be covered by
  // exactly one triangle (never twice, never zero times).
  const raster::RasterState state = raster_state({});
  const raster::TriangleSetup setup(state);
  std::vector<int> count(kWidth * kHeight, 0);
  for (std::uint32_t t = 0; t < soup.count(); ++t) {
    const raster::ClipVertex v[3] = {
        {soup.x[3 * t], soup.y[3 * t], soup.z[3 * t], soup.w[3 * t]},
        {soup.x[3 * t + 1], soup.y[3 * t + 1], soup.z[3 * t + 1], soup.w[3 * t + 1]},
        {soup.x[3 * t + 2], soup.y[3 * t + 2], soup.z[3 * t + 2], soup.w[3 * t + 2]}};
    std::vector<raster::RasterTriangle> pieces;
    setup.setup_clip(t, v, pieces);
    for (const auto& piece : pieces) {
      raster::for_each_covered_pixel(piece, [&](int px, int py) { ++count[py * kWidth + px]; });
    }
  }
  CHECK(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }));

  Soup fan;
  constexpr int kSpokes = 16;
  for (int k = 0; k < kSpokes; ++k) {
    const double a0 = 2 * M_PI * k / kSpokes, a1 = 2 * M_PI * (k + 1) / kSpokes;
    // Rim vertices rounded to 1/64 px: shared exactly between neighbouring triangles.
    auto rim = [](double a, double r, double c) {
      return c + std::round(r * std::cos(a) * 64) / 64;
    };
    fan.window_triangle(48.5, 40.5, rim(a0, 30, 48.5), rim(a0 - M_PI / 2, 30, 40.5),
                        rim(a1, 30, 48.5), rim(a1 - M_PI / 2, 30, 40.5), 0.25);
  }
  require_identical(fan);
}

TEST_CASE("glCrossCheckVerticesOnPixelCentresAndEdgesInBothWindings", "[gl]") {
  Soup soup;
  int n = 0;
  // Rectangles whose sides run exactly through pixel centres (.5) or along pixel edges (.0),
  // each split in two, in both windings; neighbours share their sides.
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 8; ++col) {
      const double offset = ((row + col) % 2) ? 0.5 : 0.0;
      const double x0 = 2 + col * 11 + offset, x1 = x0 + 11;
      const double y0 = 2 + row * 12 + offset, y1 = y0 + 12;
      const double depth = 0.1 + 0.01 * (n++);
      if ((row + col) % 3 == 0) {
        soup.window_triangle(x0, y0, x1, y0, x1, y1, depth);  // counter-clockwise
        soup.window_triangle(x0, y0, x1, y1, x0, y1, depth);
      } else {
        soup.window_triangle(x0, y0, x1, y1, x1, y0, depth);  // clockwise
        soup.window_triangle(x0, y0, x0, y1, x1, y1, depth);
      }
    }
  }
  // Diagonal edges through a row of pixel centres, and vertices exactly on centres.
  soup.window_triangle(0.5, 0.5, 60.5, 60.5, 60.5, 0.5, 0.9);
  soup.window_triangle(10.5, 70.5, 20.5, 70.5, 15.5, 75.5, 0.95);
  soup.window_triangle(30, 70, 40, 70, 35, 75, 0.95);
  require_identical(soup);
  require_identical(soup, {raster::CullMode::kBack, raster::FrontFace::kCounterClockwise});
  require_identical(soup, {raster::CullMode::kFront, raster::FrontFace::kCounterClockwise});
  require_identical(soup, {raster::CullMode::kBack, raster::FrontFace::kClockwise});
}

TEST_CASE("glCrossCheckSliversAndSubPixelTriangles", "[gl]") {
  Soup soup;
  for (int k = 0; k < 24; ++k) {
    const double y = 3 + 3 * k + dyadic(k, 0, 1, 8);
    // Long slivers 1/256 to a few 1/16 px thick, nearly horizontal and nearly vertical.
    soup.window_triangle(1, y, 95, y + dyadic(k + 100, 0, 2, 8), 95,
                         y + dyadic(k + 100, 0, 2, 8) + dyadic(k + 200, 1.0 / 256, 0.2, 8), 0.3);
    const double x = 2 + 3.875 * k;
    soup.window_triangle(x, 1, x + dyadic(k + 300, 1.0 / 256, 0.3, 8), 79, x, 79, 0.35);
  }
  // Sub-pixel triangles: all three vertices within one pixel; some contain its centre.
  for (int k = 0; k < 200; ++k) {
    const double px = std::floor(dyadic(k + 400, 0, kWidth, 0)),
                 py = std::floor(dyadic(k + 500, 0, kHeight, 0));
    soup.window_triangle(px + dyadic(k + 600, 0, 1, 8), py + dyadic(k + 700, 0, 1, 8),
                         px + dyadic(k + 800, 0, 1, 8), py + dyadic(k + 900, 0, 1, 8),
                         px + dyadic(k + 1000, 0, 1, 8), py + dyadic(k + 1100, 0, 1, 8),
                         0.4 + k / 1024.0);
  }
  require_identical(soup);
}

TEST_CASE("glCrossCheckOverlappingTrianglesWithRandomDepths", "[gl]") {
  Soup soup;
  for (int k = 0; k < 60; ++k) {
    const auto c = [&](int salt, double hi) { return dyadic(k * 31 + salt, -10, hi, 4); };
    if (k % 3 == 0) {
      // Sloped depth, within a band of its own so that no two planes meet inside the image.
      const double band = 0.05 + 0.014 * k;
      soup.window_vertex(c(1, 106), c(2, 90), band);
      soup.window_vertex(c(3, 106), c(4, 90), band + 1.0 / 256);
      soup.window_vertex(c(5, 106), c(6, 90), band + 1.0 / 128);
    } else {
      // Constant depths on a 1/1024 lattice, so exact ties happen: the first submitted wins.
      soup.window_triangle(c(1, 106), c(2, 90), c(3, 106), c(4, 90), c(5, 106), c(6, 90),
                           std::floor(dyadic(k + 77, 0.1, 0.9, 0) * 1024 / 8) * 8 / 1024);
    }
  }
  // Two identical triangles at the same depth: the first drawn keeps every pixel.
  soup.window_triangle(10, 10, 80, 20, 30, 70, 0.97);
  soup.window_triangle(10, 10, 80, 20, 30, 70, 0.97);
  require_identical(soup);
}

TEST_CASE("glCrossCheckHugeCoordinatesPartlyOffScreen", "[gl]") {
  Soup soup;
  soup.window_triangle(-8000, -7000, 8100, 300.5, 40, 8000, 0.2);
  soup.window_triangle(-6000.25, 8100, 95.5, -8100, 7000.75, 8000, 0.3);
  soup.window_triangle(-8100, 41.5, 8200, 40, 8200, 42.25, 0.4);  // a sliver across the image
  soup.window_triangle(50, -8000, 51.5, 8000, -7000, 8100, 0.5);
  require_identical(soup);
}

TEST_CASE("glCrossCheckTrianglesCrossingTheNearPlane", "[gl]") {
  // In front: z = 1, w = 2 (near distance w - z = 1); behind: z = 2, w = 1 (distance -1).
  // Clipping puts new vertices exactly half way, with w = 3/2.
  const double s = 1.0 / 8192;  // one pixel in x_ndc per unit w
  Soup soup;
  auto front = [&](double px, double py) { soup.vertex(2 * px * s, 2 * py * s, 1, 2); };
  auto behind = [&](double px, double py) { soup.vertex(px * s, py * s, 2, 1); };
  // One vertex behind: the clipped piece is a quadrilateral (two triangles, one primitive).
  front(-40, -30), front(40, -35), behind(-5, 4000);
  // Two vertices behind: a triangle remains.
  front(10, 20), behind(4000, -20), behind(-3000, 3000);
  // Behind in the other winding, reaching across the whole image.
  behind(-2000, -3000), front(-44, 35), front(44, 30);
  // Entirely behind the near plane: nothing.
  behind(-10, -10), behind(10, -10), behind(0, 10);
  require_identical(soup);
  CHECK(compare_with_gl(soup).covered > kWidth * kHeight / 4);
}

TEST_CASE("glCrossCheckDegenerateTrianglesDrawNothing", "[gl]") {
  Soup soup;
  soup.window_triangle(10, 10, 20, 20, 30, 30, 0.5);                      // collinear
  soup.window_triangle(5.5, 5.5, 5.5, 5.5, 40, 60, 0.5);                  // repeated vertex
  soup.window_triangle(7, 7, 7, 7, 7, 7, 0.5);                            // a point
  soup.window_triangle(0, 50, 96, 50.001953125, 48, 50.0009765625, 0.5);  // snaps to a line
  require_identical(soup);
  CHECK(compare_with_gl(soup).covered == 0);
}

}  // namespace
}  // namespace relief
