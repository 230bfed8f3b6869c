#include "core/height_bounds.h"

#include <algorithm>
#include <cmath>

#include "core/limits.h"

namespace relief {

HeightBounds derive_height_bounds(const NoiseLattice& lattice, const TerrainSettings& terrain,
                                  const HeightSketch* sketch) {
  double amplitude_sum = 0.0;  // a height field without the fractal sums no octave
  for (int k = terrain.first_octave; fractal_enabled(terrain) && k <= terrain.last_octave; ++k) {
    amplitude_sum += std::pow(terrain.r, -k * terrain.H);
  }
  HeightBounds bounds;
  bounds.fbm_min = amplitude_sum * std::min(0.0, static_cast<double>(lattice.min_value));
  bounds.fbm_max = amplitude_sum * std::max(0.0, static_cast<double>(lattice.max_value));
  const double slack =
      limits::kHeightBoundSlack * std::max(std::abs(bounds.fbm_min), std::abs(bounds.fbm_max));
  bounds.world_min = terrain.base_height + terrain.amplitude * (bounds.fbm_min - slack);
  bounds.world_max = terrain.base_height + terrain.amplitude * (bounds.fbm_max + slack);
  if (added_height_field(terrain) != nullptr && sketch != nullptr) {
    const double lo = sketch->min_height, hi = sketch->max_height;
    const double sketch_slack = limits::kHeightBoundSlack * std::max(std::abs(lo), std::abs(hi));
    bounds.world_min += lo - sketch_slack;
    bounds.world_max += hi + sketch_slack;
  }
  return bounds;
}

}  // namespace relief
