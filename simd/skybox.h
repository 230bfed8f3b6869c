// The skybox lookup (core/skybox.h) as a Highway kernel for float over directions held as
// structure-of-arrays spans: the same operations as skybox_radiance<float>, in the same order,
// so every radiance is bit-identical to the scalar reference on every target (stage 8's sky
// and water reflection read it through simd/sky-inl.h; this entry serves whole arrays).
#pragma once

#include <span>

#include "core/skybox.h"

namespace relief::simd {

// rgb[3 k + c] = skybox_radiance<float>(box, {x[k], y[k], z[k]})[c] for k < x.size(); the
// spans x, y, z of one length and rgb three times it (std::invalid_argument otherwise, or for
// a box whose texels are not 6 faces of size^2 RGB). Any direction, a NaN or infinity included,
// gives the scalar code's finite result.
void skybox_radiances(const Skybox& box, std::span<const float> x, std::span<const float> y,
                      std::span<const float> z, std::span<float> rgb);

}  // namespace relief::simd
