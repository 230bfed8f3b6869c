// Sky light's per-pixel step (core/sky_horizons.h) as a Highway kernel for float: the same
// operations as sky_visibility<float>, in the same order, on as many pixels per step as the
// target's vectors hold, so the shares and the work counters are bit-identical to the scalar
// reference on every target.
#pragma once

#include <cstdint>
#include <span>

#include "core/sky_horizons.h"
#include "core/sun_horizons.h"

namespace relief::simd {

// Over a rectangle: pixel (i, j), 0 <= i < width, 0 <= j < height, has index k = j * stride + i
// into every span. Where covered[k] != 0xffffffff writes share[k] = sky_visibility<float>(p, c,
// dx[k], dz[k]) and adds to `work` exactly what the scalar code adds; leaves the other pixels'
// shares alone and uses none of their attributes. Precondition: p.sky, the cache swept.
void sky_shares(const ShadowParams<float>& p, const SunHorizonCache<float>& c,
                std::span<const std::uint32_t> covered, std::span<const float> dx,
                std::span<const float> dz, int width, int height_px, int stride,
                std::span<float> share, SkyWork& work);

}  // namespace relief::simd
