// Stages 1-2 (§4.1, the projected grid) as a Highway kernel: project_domain<float>
// (core/projected_domain.h) over whole rows, the projector rays' footprints, the spacing from
// the four neighbours and the octave count nu with log2_det, in the scalar code's operations
// and order: bit-identical on every target.
#pragma once

#include "core/grid_buffers.h"
#include "core/planet_plan.h"
#include "core/projected_domain.h"
#include "core/stage_params.h"

namespace relief::simd {

// Precondition: params.pitch is a multiple of 16 (GridLayout's row alignment).
void project_domain(const DomainParams<float>& params, const DomainRows<float>& table,
                    RowRange rows, DomainSpans<float> out);

// Stage 2 on a planet: project_planet_domain<float> (core/planet_domain.h), planet_footprint
// per lane (atan2_det through simd/det_trig-inl.h), bit-identical on every target. The same
// precondition.
void project_planet_domain(const DomainParams<float>& params, const PlanetParams<float>& planet,
                           const DomainRows<float>& table, RowRange rows, DomainSpans<float> out);

}  // namespace relief::simd
