// sRGB transfer function (IEC 61966-2-1), for writing linear radiance as 8-bit images.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace relief {

// Linear [0, 1] to sRGB-encoded [0, 1]; inputs outside [0, 1] are clipped, as a display does.
inline double srgb_encode(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// sRGB decoding, the inverse of srgb_encode on [0, 1].
inline double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// The 8-bit code of a linear value: the number of decision points
// t_k = srgb_decode((k + 1/2) / 255), k = 0..254, at or below it, i.e. round(255 srgb_encode(x))
// without a pow per pixel (a binary search over 255 doubles computed once).
inline std::uint8_t srgb_byte(double linear) {
  static const std::array<double, 255> kDecisionPoints = [] {
    std::array<double, 255> points{};
    for (int k = 0; k < 255; ++k) {
      points[k] = srgb_decode((k + 0.5) / 255.0);
    }
    return points;
  }();
  return static_cast<std::uint8_t>(
      std::upper_bound(kDecisionPoints.begin(), kDecisionPoints.end(), linear) -
      kDecisionPoints.begin());
}

}  // namespace relief
