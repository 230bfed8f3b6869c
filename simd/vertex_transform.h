// Stage 5 as Highway kernels: transform_vertices<float> and light_vertices<float>
// (core/vertex_transform.h), the same products and sums in the same order, bit-identical on
// every target.
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

// light_vertices<float> (core/vertex_transform.h), bit-identical on every target.
void light_vertices(const TransformParams<float>& params, IndexRange range,
                    std::span<const float> nx, std::span<const float> ny, std::span<const float> nz,
                    std::span<const std::uint8_t> need, std::span<float> lambert);

}  // namespace relief::simd
