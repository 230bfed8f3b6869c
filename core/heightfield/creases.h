// Miller's creases measured (docs/heightfields.md, "Creasing"): a crease is a slope
// discontinuity, and on a grid of spacing h it shows in the second difference
// |h(x - 1) - 2 h(x) + h(x + 1)|, which is O(h) across a crease and O(h^2) where the surface is
// C1 with bounded curvature. Subdivision creases lie along the lines the coarse levels drew:
// the columns and rows at multiples of side / 2^l for the first levels l.
#pragma once

#include <vector>

#include "core/heightfield/periodic_grid.h"

namespace relief {

// Per point, the largest absolute second difference along x, along z and along the two
// diagonals (the diagonal ones halved: their spacing is sqrt 2 and a second difference grows as
// the spacing squared). Periodic.
std::vector<float> crease_map(const PeriodicGrid& grid);

// Across the lines of the first `levels` subdivision levels (x or z an odd multiple of
// side / 2^l, l = 1 ... levels), the mean absolute second difference across the line (along x
// for a column, along z for a row), divided by the mean over every point of the same second
// difference: about 1 without creases, well above 1 with them. 0 for a flat map.
double crease_ratio(const PeriodicGrid& grid, int levels);

// The largest absolute second difference along x or z anywhere.
double largest_second_difference(const PeriodicGrid& grid);

}  // namespace relief
