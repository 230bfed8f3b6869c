// A Perlin height map (Mekala's terrain, Perlin 1985 and 2002): gradient noise summed over
// octaves on a periodic grid, octave o with 2^o times the base lattice's cells across the map
// and amplitude amplitude 2^(-o H), up to the octave whose cell is two samples wide. Each
// lattice point's gradient is one of eight unit directions (the axes and diagonals) chosen by
// the counter hash (docs/noise-lattice.md, stream 2, method 3); the blend is Perlin's quintic
// fade 6t^5 - 15t^4 + 10t^3. The lattice wraps, so the map tiles.
#pragma once

#include <cstdint>
#include <functional>

#include "core/heightfield/periodic_grid.h"

namespace relief {

struct PerlinSettings {
  int side = 0;            // a power of two, at least 2
  int base_cells = 4;      // the first octave's cells across the map: a power of two <= side / 2
  double amplitude = 1.0;  // of the first octave
  double roughness = 0.8;  // H: octave o's amplitude is amplitude 2^(-o H)
  std::uint64_t seed = 1;
  int max_octaves = 1 << 30;  // at most this many octaves (the first ones)
};

// The octaves base_cells, 2 base_cells, ... <= side / 2. `progress(octave, octaves)`.
PeriodicGrid perlin_field(const PerlinSettings& settings,
                          const std::function<void(int, int)>& progress = {});

}  // namespace relief
