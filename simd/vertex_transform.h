// Stage 5 as a Highway kernel: transform_vertices<float> (core/vertex_transform.h), the same
// products and sums in the same order, bit-identical on every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/stage_params.h"
#include "core/vertex_transform.h"

namespace relief::simd {

void transform_vertices(const TransformParams<float>& params, IndexRange range,
                        std::span<const float> dx, std::span<const float> dz,
                        std::span<const float> height, std::span<const std::uint8_t> need,
                        ClipSpans<float> clip);

}  // namespace relief::simd
