// Proto-texture layer weights (§4.2's "height/slope-dependent weighting function"; Scape's
// ranged layers with a spread and noise-dithered transitions).
//
// Slope is the paper's |grad h| (§4.2: "at steep rock formations (where |grad H| is large)"),
// not Mekala's up . N: it is what stage 4 computes, and a layer's range in degrees maps to it
// through tan, once per frame. Each layer's weight is the product of four ramps (rising and
// falling in height, rising and falling in slope), each a cubic step of width 2 spread
// centred on its edge, the ramp's position shifted by the dither offset:
//   ramp(x) = smooth01((x - start) / (end - start) + dither_offset)
// The weights are then renormalised to sum to one; where every layer is zero (a gap the scene
// left in its ranges) all layers share equally.
#pragma once

#include "core/limits.h"
#include "core/stage_params.h"

namespace relief {

// Writes params.layer_count weights summing to 1. `height` is camera-relative, as the plan's
// ramps are; dither_offset = dither amount * noise / 2.
template <class Real>
void layer_weights(const ShadeParams<Real>& params, Real height, Real slope, Real dither_offset,
                   Real weights[limits::kMaxMaterialLayers]);

}  // namespace relief
