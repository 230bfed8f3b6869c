// Stage 3's second part, §3's low-frequency sketch (core/height_sketch.h), as a Highway kernel:
// add_sketch<float>'s operations in its order on a vector of points, bit-identical to it on
// every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/height_sketch.h"

namespace relief::simd {

// add_sketch<float> (core/height_sketch.h) over `range`, with the same preconditions and results.
void add_sketch(const SketchParams<float>& params, std::span<const float> heights, IndexRange range,
                std::span<const float> dx, std::span<const float> dz, std::span<const float> nu,
                std::span<const std::uint8_t> mask, std::span<float> height);

}  // namespace relief::simd
