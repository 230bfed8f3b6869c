// The float error of stage 3 at the grid's vertices (relief reference --stats, relief sweep):
// a float backend's heights against the double fBm evaluated at the same domain points and
// octave counts (the float frame's dx, dz and nu, converted exactly to double), so that the
// figure is the fractal's own rounding, not the projected grid's (whose float footprints lie a
// rounding away from the double ones). bench/precision_report.cc compares whole double frames.
#pragma once

#include <cstddef>

#include "core/lattice.h"
#include "core/scene/scene.h"
#include "pipeline/frame.h"

namespace relief {

struct VertexHeightError {
  std::size_t vertices = 0;  // valid vertices compared
  double max = 0;            // world units
  double rms = 0;            // world units
  double amplitude = 1;      // terrain.amplitude, for relative figures
};

// `backend`: a float backend (reference, simd or gl). Every valid vertex of the scene's grid,
// none culled.
VertexHeightError vertex_height_error(const Scene& scene, const NoiseLattice& lattice,
                                      Backend backend = Backend::kSimd,
                                      const HeightSketch* sketch = nullptr);

}  // namespace relief
