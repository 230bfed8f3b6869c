// The triangles of one GeoMipMapping tile (core/heightfield/geomipmap.h), in tile-local lattice
// steps (u along x, v along z, both in [0, T]): one generator for the mesh
// (geomipmap_mesh.cc) and for the levels' errors (geomipmap.cc), so that the error a level is
// chosen by is measured on the triangles that are drawn.
//
// At spacing s = 2^L < T: the interior, cells of s from s to T - s, each split by the diagonal
// from its (0, 0) to its (s, s) corner; then the border ring, one trapezoid per side between
// the tile's edge at that side's spacing (s, or a coarser neighbour's) and the inner line at s.
// At s = T: two triangles.
#pragma once

#include <array>
#include <utility>
#include <vector>

namespace relief::geomipmap {

using LatticeStep = std::array<int, 2>;  // (u, v)

// Emits (a, b, c) counter-clockwise seen from +y: the cross product's y, (b - a) x (c - a),
// positive with (u, v) along (x, z); a triangle the other way round is emitted as (a, c, b).
template <class Emit>
void emit_counter_clockwise(LatticeStep a, LatticeStep b, LatticeStep c, Emit& emit) {
  const long long cross_y = static_cast<long long>(b[1] - a[1]) * (c[0] - a[0]) -
                            static_cast<long long>(b[0] - a[0]) * (c[1] - a[1]);
  if (cross_y < 0)
    std::swap(b, c);
  emit(a, b, c);
}

template <class Emit>
void interior_triangles(int tile_cells, int s, Emit&& emit) {
  for (int v = s; v < tile_cells - s; v += s) {
    for (int u = s; u < tile_cells - s; u += s) {
      emit_counter_clockwise({u, v}, {u + s, v}, {u + s, v + s}, emit);
      emit_counter_clockwise({u, v}, {u + s, v + s}, {u, v + s}, emit);
    }
  }
}

// The border ring's trapezoid of one side (0: v = 0, 1: u = T, 2: v = T, 3: u = 0), its edge at
// spacing `edge` (a multiple of s, at most T), s < T. The outer edge from t = 0 to T at spacing
// `edge`, the inner line (offset s inward) from s to T - s at spacing s (one point when
// s = T / 2), joined by a zipper: each triangle joins the current outer and inner points with
// the next of one of them, the outer first where its next point is no farther along; both
// chains are monotone and the inner lies strictly inside, so the triangles tile the trapezoid
// without overlap, and neighbouring sides share the diagonal from the corner to the inner
// line's end.
template <class Emit>
void side_triangles(int tile_cells, int s, int side, int edge, Emit&& emit) {
  const int T = tile_cells;
  const auto at = [&](int t, bool inner) -> LatticeStep {
    switch (side) {
      case 0:
        return {t, inner ? s : 0};
      case 1:
        return {inner ? T - s : T, t};
      case 2:
        return {t, inner ? T - s : T};
      default:
        return {inner ? s : 0, t};
    }
  };
  std::vector<int> outer, inner;
  for (int t = 0; t <= T; t += edge)
    outer.push_back(t);
  for (int t = s; t <= T - s; t += s)
    inner.push_back(t);
  std::size_t a = 0, b = 0;
  while (a + 1 < outer.size() || b + 1 < inner.size()) {
    const bool step_outer =
        a + 1 < outer.size() && (b + 1 == inner.size() || outer[a + 1] <= inner[b + 1]);
    if (step_outer) {
      emit_counter_clockwise(at(outer[a], false), at(outer[a + 1], false), at(inner[b], true),
                             emit);
      ++a;
    } else {
      emit_counter_clockwise(at(outer[a], false), at(inner[b], true), at(inner[b + 1], true), emit);
      ++b;
    }
  }
}

// The whole tile at spacing s = 2^L with its sides' spacings (v = 0, u = T, v = T, u = 0).
template <class Emit>
void tile_triangles(int tile_cells, int s, const std::array<int, 4>& edges, Emit&& emit) {
  const int T = tile_cells;
  if (s == T) {
    emit_counter_clockwise({0, 0}, {T, 0}, {T, T}, emit);
    emit_counter_clockwise({0, 0}, {T, T}, {0, T}, emit);
    return;
  }
  interior_triangles(T, s, emit);
  for (int side = 0; side < 4; ++side)
    side_triangles(T, s, side, edges[static_cast<std::size_t>(side)], emit);
}

}  // namespace relief::geomipmap
