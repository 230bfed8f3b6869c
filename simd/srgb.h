// Stage 9's sRGB encoding as a Highway kernel: srgb_byte (core/srgb.h) of many values at once,
// bit for bit, with two table lookups (gathers) per value instead of a search.
#pragma once

#include <cstdint>
#include <span>

namespace relief::simd {

// out[k] = srgb_byte(linear[k]) for every k; the spans have the same size.
void encode_srgb(std::span<const float> linear, std::span<std::uint8_t> out);

}  // namespace relief::simd
