// The frustum outcodes of the culling stages (core/vertex_culling.h) as a Highway kernel:
// vertex_outcodes<float>, the same products, sums and comparisons in the same order, so the
// same bits on every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/frame_plan.h"
#include "core/vertex_culling.h"

namespace relief::simd {

// vertex_outcodes<float> of rows [rows.begin, rows.end): `height` empty for the segment of the
// height bounds, else the vertices' own heights.
void vertex_outcodes(const CullParams<float>& params, RowRange rows, std::span<const float> dx,
                     std::span<const float> dz, std::span<const float> height,
                     std::span<const std::uint8_t> valid, std::span<std::uint8_t> outcode);

}  // namespace relief::simd
