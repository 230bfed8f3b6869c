// Stage 4 (§4.1 second pass) as a Highway kernel: surface_pass<float> (core/surface.h) over
// whole rows, the same differences, scalings and selections in the same order, bit-identical
// on every target.
#pragma once

#include "core/grid_buffers.h"
#include "core/stage_params.h"
#include "core/surface.h"

namespace relief::simd {

void surface_pass(const SurfaceParams<float>& params, RowRange rows, SurfaceInputs<float> in,
                  SurfaceSpans<float> out);

}  // namespace relief::simd
