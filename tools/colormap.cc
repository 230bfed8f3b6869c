#include "tools/colormap.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

}  // namespace

Rgb8 heat_color(double t) {
  if (std::isnan(t)) {
    return {255, 0, 255};
  }
  // Control points of a turbo-like ramp, evenly spaced in t.
  static constexpr double kStops[][3] = {{0.19, 0.07, 0.23}, {0.16, 0.47, 0.93}, {0.10, 0.85, 0.72},
                                         {0.49, 0.98, 0.27}, {0.93, 0.85, 0.20}, {0.98, 0.45, 0.10},
                                         {0.64, 0.05, 0.01}};
  constexpr int kSegments = 6;
  const double x = std::clamp(t, 0.0, 1.0) * kSegments;
  const int k = std::min(static_cast<int>(x), kSegments - 1);
  const double f = x - k;
  Rgb8 out;
  for (int c = 0; c < 3; ++c) {
    out[c] = to_byte(kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c]));
  }
  return out;
}

Rgb8 gray_color(double t) {
  const std::uint8_t v = to_byte(std::isnan(t) ? 0.0 : t);
  return {v, v, v};
}

Rgb8 magma_color(double t) {
  if (std::isnan(t)) {
    return {255, 255, 255};
  }
  static constexpr std::uint8_t kStops[][3] = {
      {0x00, 0x00, 0x04}, {0x1d, 0x11, 0x47}, {0x51, 0x12, 0x7c},
      {0x82, 0x26, 0x81}, {0xb6, 0x36, 0x79}, {0xe6, 0x51, 0x64},
      {0xfb, 0x88, 0x61}, {0xfe, 0xc2, 0x87}, {0xfc, 0xfd, 0xbf}};
  constexpr int kSegments = 8;
  const double x = std::clamp(t, 0.0, 1.0) * kSegments;
  const int k = std::min(static_cast<int>(x), kSegments - 1);
  const double f = x - k;
  Rgb8 out;
  for (int c = 0; c < 3; ++c) {
    out[c] = to_byte((kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c])) / 255.0);
  }
  return out;
}

}  // namespace relief
