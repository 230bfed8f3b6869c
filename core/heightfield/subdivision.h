// Height maps by recursive subdivision, the three methods Miller compares ("The Definition and
// Rendering of Terrain Maps", SIGGRAPH 1986, §2), on a periodic grid that doubles its side at
// every level:
//   - triangle-edge: each square split along its diagonal; every edge's midpoint is the mean of
//     the edge's two ends plus a random displacement. Context independent: no value crosses an
//     edge, hence Miller's creases along the x and z lines and the diagonals.
//   - diamond-square (Fournier, Fussell and Carpenter 1982): a square's centre from its four
//     corners, then each diamond's centre (an edge midpoint) from its four tips, each plus a
//     displacement. Context dependent, yet the two-tier scheme still creases.
//   - square-square (Miller's proposal, after the CAD subdivision of Doo-Sabin and Catmull-
//     Clark): each value spawns four on a grid of half the spacing, each the 9:3:3:1 mix of the
//     four nearest old values (nearest weighted most) plus a displacement; without the
//     displacements the limit is the biquadratic B-spline surface, C1 (no creases), which does
//     not pass through its control points.
// The displacement at spacing d (in units of the coarse grid's spacing) has standard deviation
// amplitude * d^H (Miller's S = k 2^(-iH)): H the roughness. Its values are Gaussian to
// three moments: the sum of four uniforms from one counter hash (docs/noise-lattice.md, stream
// 2), centred and scaled to variance 1 (Irwin-Hall), exact in double. So a map is a pure
// function of its control points, method, levels, amplitude, H and seed: the same bits on every
// machine, in any order.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

#include "core/heightfield/periodic_grid.h"

namespace relief {

enum class Subdivision { kTriangleEdge, kDiamondSquare, kSquareSquare };

std::string_view subdivision_name(Subdivision method);  // "triangle-edge", ...

struct SubdivisionSettings {
  Subdivision method = Subdivision::kSquareSquare;
  int levels = 0;          // each doubles the side
  double amplitude = 1.0;  // displacement's standard deviation at the coarse spacing (>= 0)
  double roughness = 0.8;  // H (>= 0): the deviation at spacing d is amplitude d^H
  std::uint64_t seed = 1;
  // Levels after this one add no displacement: the map is the method's interpolant of the
  // first random levels (Miller's test of a method: its creases are the interpolant's).
  int random_levels = 1 << 30;
};

// The coarse grid's control points subdivided `levels` times: side coarse.side * 2^levels.
// Preconditions: coarse.side >= 1, the result's side at most 2^15. `progress(level, levels)`
// after each level.
PeriodicGrid subdivide(const PeriodicGrid& coarse, const SubdivisionSettings& settings,
                       const std::function<void(int, int)>& progress = {});

// The displacement's unit-variance random value of point `index` at `level` (1-based).
double subdivision_gaussian(std::uint64_t seed, Subdivision method, int level, std::uint64_t index);

}  // namespace relief
