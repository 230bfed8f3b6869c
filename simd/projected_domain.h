// Stages 1-2 (§4.1, the projected grid) as a Highway kernel: project_domain<float>
// (core/projected_domain.h) over whole rows, the projector rays' footprints, the spacing from
// the four neighbours and the octave count nu with log2_det, in the scalar code's operations
// and order: bit-identical on every target.
#pragma once

#include "core/grid_buffers.h"
#include "core/projected_domain.h"
#include "core/stage_params.h"

namespace relief::simd {

// Precondition: params.pitch is a multiple of 16 (GridLayout's row alignment).
void project_domain(const DomainParams<float>& params, const DomainRows<float>& table,
                    RowRange rows, DomainSpans<float> out);

}  // namespace relief::simd
