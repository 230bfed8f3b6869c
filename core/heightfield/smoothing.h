// Smoothing passes over a periodic height map (castledragmire's diamond-square "with smoothing",
// Mekala's smoothing pass): each pass the separable [1 2 1] / 4 filter along x, then along z,
// wrapping at the edges, in double, rounded to float once per pass and axis.
#pragma once

#include <functional>

#include "core/heightfield/periodic_grid.h"

namespace relief {

// `progress(pass, passes)` after each pass.
void smooth_height_map(PeriodicGrid& grid, int passes,
                       const std::function<void(int, int)>& progress = {});

}  // namespace relief
