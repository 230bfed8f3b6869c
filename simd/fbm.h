// Stage 3 (Eq. 1, §2.2 warping, §4.1 fractional octave) as a Highway kernel: the same
// operations as core/fbm.cc, in the same order, on as many points per step as the target's
// vectors hold, so every buffer is bit-identical to the scalar reference on every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/fbm.h"

namespace relief::simd {

// evaluate_fbm<float> (core/fbm.h) over `range`, with the same preconditions and results.
FbmWork evaluate_fbm(const FbmParams<float>& params, const NoiseLattice& lattice, IndexRange range,
                     std::span<const float> dx, std::span<const float> dz,
                     std::span<const float> nu, std::span<const std::uint8_t> mask,
                     std::span<float> height);

}  // namespace relief::simd
