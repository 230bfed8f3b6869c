// Stage 7: attribute resolve (docs/architecture.md). For every covered pixel: the
// perspective-correct barycentrics of the triangle that won it, the interpolated vertex attributes,
// and their screen-space derivatives, computed the way a GPU runs fragment shaders: in 2 x 2 quads,
// the winning triangle's attribute plane evaluated at the quad partners too ("helper pixels"),
// whether or not that triangle covers them.
//
// Barycentrics come straight from the original (unclipped) triangle in homogeneous window
// coordinates (X, Y, W) = (x s + w t, y s + w t, w): the weights b with sum b_i (X_i - u W_i)
// = sum b_i (Y_i - v W_i) = 0 and sum b_i = 1 are b ~ (e1 x e2, e2 x e0, e0 x e1) with
// e_i = (X_i - u W_i, Y_i - v W_i) (2D homogeneous rasterisation, Olano & Greer 1997). They
// are the weights of clip-space interpolation, i.e. perspective-correct, defined for triangles
// crossing the near plane as well, and for helper pixels outside the triangle.
// Derivatives are GL's dFdxFine/dFdyFine: differences within the pixel's row and column of
// its quad (quads start at even x and y).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/raster_types.h"
#include "raster/topology.h"

namespace relief::raster {

// Homogeneous window position (X, Y, W) of each vertex.
class VertexPositions {
 public:
  static VertexPositions from_clip(ClipVertices clip, const Viewport& viewport);
  static VertexPositions from_window(WindowVertices window);

  void get(std::uint32_t v, double& x, double& y, double& w) const;

 private:
  std::span<const float> x_, y_, w_;
  bool window_ = false;
  double scale_x_ = 1, scale_y_ = 1, translate_x_ = 0, translate_y_ = 0;
};

struct ResolvedFrame {
  int width = 0;
  int height = 0;
  AlignedVector<float> b0, b1, b2;          // perspective-correct barycentrics; 0 where uncovered
  std::vector<AlignedVector<float>> value;  // per attribute stream: value at the pixel,
  std::vector<AlignedVector<float>> ddx;    // and its fine derivatives (the first streams)
  std::vector<AlignedVector<float>> ddy;
};

// `attributes[s][v]` is stream s at vertex v; the first `derivative_streams` streams also get
// their derivatives (out.ddx, out.ddy have that many entries). Uncovered pixels resolve to zeros.
// Division domain: sum of the three cross products != 0 (it vanishes only where the pixel's ray is
// parallel to the triangle's plane); a covered pixel failing it gets b = (1/3, 1/3, 1/3),
// a helper pixel failing it gives a zero derivative. Parallel over quad rows; the result does
// not depend on the thread count.
template <class Source>
void resolve(const VisibilityBuffer& visibility, const VertexPositions& positions,
             const Source& source, std::span<const std::span<const float>> attributes,
             std::size_t derivative_streams, ResolvedFrame& out);

struct PerspectivePlane;

// The interpolation weights of one pixel of a 2 x 2 quad: its own perspective-correct
// barycentrics (1/3 each where undefined), those of its quad partners in the same row (bx) and
// the same column (by) where defined, and the signs that turn partner minus pixel into GL's
// dFdxFine / dFdyFine (right column minus left, top row minus bottom). Quads start at even
// coordinates.
struct QuadWeights {
  double b[3], bx[3], by[3];
  bool has_x = false, has_y = false;
  double sign_x = 1, sign_y = 1;

  // a(b) = sum b_i a_i over the triangle's vertex values a0, a1, a2, in double.
  static double at(const double weights[3], double a0, double a1, double a2) {
    return weights[0] * a0 + weights[1] * a1 + weights[2] * a2;
  }
};

QuadWeights quad_weights(const PerspectivePlane& plane, int px, int py);

// The three cross products above are linear in (u, v) (the u v terms cancel):
// l_i(u, v) = k_i + ku_i u + kv_i v, so a triangle's are set up once and evaluated per pixel.
struct PerspectivePlane {
  double k[3], ku[3], kv[3];

  PerspectivePlane(const double x[3], const double y[3], const double w[3]);
  // The perspective-correct barycentrics at window point (u, v); false where undefined
  // (l_0 + l_1 + l_2 = 0, see resolve).
  bool barycentrics(double u, double v, double b[3]) const;
};

}  // namespace relief::raster
