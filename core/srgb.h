// sRGB transfer function (IEC 61966-2-1), for writing linear radiance as 8-bit images.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
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

namespace srgb_detail {

// t_k = srgb_decode((k + 1/2) / 255), k = 0..254: the linear values where the 8-bit code steps.
inline const std::array<double, 255>& decision_points() {
  static const std::array<double, 255> points = [] {
    std::array<double, 255> p{};
    for (int k = 0; k < 255; ++k) {
      p[k] = srgb_decode((k + 0.5) / 255.0);
    }
    return p;
  }();
  return points;
}

// For each float in (0, 1) sharing its top 16 bits (a bucket of 1/128 relative width): the
// code of the bucket's smallest value. A bucket spans at most two codes, so one or two
// comparisons finish the job.
inline const std::array<std::uint8_t, 0x3f81>& bucket_codes() {
  static const std::array<std::uint8_t, 0x3f81> codes = [] {
    std::array<std::uint8_t, 0x3f81> c{};
    const auto& points = decision_points();
    for (std::uint32_t bucket = 0; bucket < c.size(); ++bucket) {
      const double lowest = std::bit_cast<float>(bucket << 16);
      c[bucket] = static_cast<std::uint8_t>(std::upper_bound(points.begin(), points.end(), lowest) -
                                            points.begin());
    }
    return c;
  }();
  return codes;
}

// The same search without a loop, for vector kernels: per bucket, its first code widened to 32
// bits and the least float at which the code rises by one (a bucket spans at most two codes:
// tests/core/shading_test.cc checks every bucket), or 2 where it does not rise inside the bucket.
// A float x is >= the double t_k exactly when it is >= the least float >= t_k.
struct BucketSteps {
  std::array<std::int32_t, 0x3f81> code{};
  std::array<float, 0x3f81> next_at{};
};

inline const BucketSteps& bucket_steps() {
  static const BucketSteps steps = [] {
    BucketSteps s;
    const auto& points = decision_points();
    const auto& codes = bucket_codes();
    for (std::size_t bucket = 0; bucket < codes.size(); ++bucket) {
      s.code[bucket] = codes[bucket];
      s.next_at[bucket] = 2.0f;
      if (codes[bucket] < 255) {
        const double t = points[codes[bucket]];
        float f = static_cast<float>(t);
        if (double(f) < t) {
          f = std::nextafter(f, 2.0f);
        }
        s.next_at[bucket] = f;
      }
    }
    return s;
  }();
  return steps;
}

}  // namespace srgb_detail

// The 8-bit code of a linear value: the number of decision points t_k at or below it, i.e.
// round(255 srgb_encode(x)) without a pow per pixel. Below 0 (and NaN): 0; from 1 up: 255.
inline std::uint8_t srgb_byte(float linear) {
  if (!(linear > 0.0f)) {
    return 0;
  }
  if (linear >= 1.0f) {
    return 255;
  }
  const auto& points = srgb_detail::decision_points();
  unsigned code = srgb_detail::bucket_codes()[std::bit_cast<std::uint32_t>(linear) >> 16];
  while (code < 255 && double(linear) >= points[code]) {
    ++code;
  }
  return static_cast<std::uint8_t>(code);
}

}  // namespace relief
