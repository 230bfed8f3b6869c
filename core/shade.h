// Stage 8: proto-texture shading (docs/architecture.md; §4.2, §4.3 and the other seeds' additions),
// per pixel over rows of the image, from the resolved attributes of stage 7.
//
// Covered pixel: layer weights (layer_weights.h) from the height, the slope |grad h| and the
// dithering noise; each layer's proto-texture sampled trilinearly at the LOD of GL's formula
// from the quad derivatives of the world position, projected from above or, with triplanar
// on, from the three axes weighted by the squared normal (Mekala, Scape); lit by the sun
// (Lambert, optional Phong per layer), the hemispherical sky light and an ambient term
// (Scape); covered by water where it lies below the water level (water.h); then fogged by
// distance (sky.h). Uncovered pixel: the sky, or open water below the horizon. Result: linear
// radiance times the exposure.
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/shading_plan.h"

namespace relief {

// Per-pixel inputs, row 0 the bottom of the image; all spans width * height long.
struct ShadingInputs {
  std::span<const std::uint32_t> primitive;  // 0xffffffff where no terrain covers the pixel
  std::span<const float> dx, dz, height;     // camera-relative x, height (y), z
  std::span<const float> dx_ddx, dx_ddy, dz_ddx, dz_ddy, height_ddx, height_ddy;
  std::span<const float> nx, ny, nz;  // interpolated normal (renormalised here)
  std::span<const float> slope;
  std::span<const float> water_depth;  // interpolated per-vertex depth (§4.3)
};

// Writes rows [rows.begin, rows.end) of `rgb` (3 values per pixel). Output finite everywhere.
template <class Real>
void shade_pixels(const ShadingPlan& plan, const ShadingInputs& in, RowRange rows,
                  std::span<Real> rgb);

}  // namespace relief
