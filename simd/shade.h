// Stage 8 (core/shade.h) as a Highway kernel for float: terrain_radiance and
// background_radiance with the same operations as core/shade.cc, core/layer_weights.cc,
// core/proto_texture.cc, core/water.cc, core/sky.cc and core/det_math.h, in the same order, on
// as many pixels per step as the target's vectors hold, so the radiance and the work counters
// are bit-identical to the scalar reference on every target.
#pragma once

#include <span>

#include "core/shade.h"
#include "core/stage_params.h"

namespace relief::simd {

// Stage 8 over a rectangle: pixel (x0 + i, y0 + j), 0 <= i < width, 0 <= j < height, has index
// k = j * stride + i into every span of `in` and into `rgb` (3 floats per pixel). Writes the
// radiance times p.exposure, bit-identical to terrain_radiance<float> (covered pixels,
// in.primitive[k] != 0xffffffff) and background_radiance<float>(p, r, x0 + i, y0 + j) (the
// others) times the exposure, and adds to `work` exactly the counts the scalar code adds.
// Reads only the pixels of the rectangle (the attributes of covered pixels only; water_depth
// and water_sun only when p.water_enabled && p.terrain_water).
void shade_rect(const ShadeParams<float>& p, const ShadeResources& r, const ShadingInputs& in,
                int x0, int y0, int width, int height, int stride, std::span<float> rgb,
                ShadeWork& work);

}  // namespace relief::simd
