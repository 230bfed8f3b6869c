// The range of heights the terrain can take, derived from the fBm (Eq. 1), not guessed: §4.1
// needs "the maximum height of the terrain ... a priori" to build the projector frustum.
//
// Every octave samples S, a convex combination of lattice values (interpolant.h), so S lies in
// [Lmin, Lmax]. The LOD weights of the octaves lie in [0, 1] and the amplitudes r^(-kH) are
// positive, hence
//   sum_k a_k min(Lmin, 0) <= fBm <= sum_k a_k max(Lmax, 0),   k = k0 .. k1.
// §3's sketch adds a convex combination of its texels (height_sketch.h): the world bounds grow
// by the texels' extremes, widened by kHeightBoundSlack of their magnitude for float's rounding.
// Domain warping moves where S is sampled, never its range, so the bound holds warped too. A
// height field (terrain.heightfield) is such a sketch; without its fractal no octave is summed
// and the fBm bound is [0, 0].
#pragma once

#include "core/height_sketch.h"
#include "core/lattice.h"
#include "core/scene/scene.h"

namespace relief {

struct HeightBounds {
  double fbm_min = 0;  // bounds of the dimensionless sum of Eq. 1
  double fbm_max = 0;
  double world_min = 0;  // base_height + amplitude * fbm bound, widened by kHeightBoundSlack
  double world_max = 0;
};

HeightBounds derive_height_bounds(const NoiseLattice& lattice, const TerrainSettings& terrain,
                                  const HeightSketch* sketch = nullptr);

}  // namespace relief
