// A planet's bend (core/planet_bend.h) as Highway kernels: bend_vertices<float> and
// bend_normals<float>, the same operations in the same order (sin_cos_det and sin_det lane by
// lane), bit-identical on every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/planet_plan.h"

namespace relief::simd {

void bend_vertices(const PlanetParams<float>& planet, IndexRange range, std::span<const float> dx,
                   std::span<const float> dz, std::span<const float> height,
                   std::span<const std::uint8_t> valid, BentSpans<float> out);

void bend_normals(const PlanetParams<float>& planet, IndexRange range, std::span<const float> dx,
                  std::span<const float> dz, std::span<const std::uint8_t> valid,
                  std::span<float> nx, std::span<float> ny, std::span<float> nz);

}  // namespace relief::simd
