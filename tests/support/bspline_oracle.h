// The tests' own uniform cubic B-spline (core/height_sketch.h's definition, written from it, not
// shared with it): samples w x h (row j at j * w), texel centres at integers, the 4 x 4 taps
// clamped to the edge, weights of t in [0, 1) as the basis functions, in double.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace relief::test {

template <class Sample>
double bspline_at(const Sample* samples, int w, int h, double s, double t) {
  const auto weights = [](double f, double out[4]) {
    out[0] = (1 - f) * (1 - f) * (1 - f) / 6;
    out[1] = (3 * f * f * f - 6 * f * f + 4) / 6;
    out[2] = (-3 * f * f * f + 3 * f * f + 3 * f + 1) / 6;
    out[3] = f * f * f / 6;
  };
  const double fs = std::floor(s), ft = std::floor(t);
  double ws[4], wt[4];
  weights(s - fs, ws);
  weights(t - ft, wt);
  double sum = 0;
  for (int b = 0; b < 4; ++b) {
    const int z = std::clamp(int(ft) - 1 + b, 0, h - 1);
    for (int a = 0; a < 4; ++a) {
      const int x = std::clamp(int(fs) - 1 + a, 0, w - 1);
      sum += wt[b] * ws[a] * double(samples[std::size_t(z) * std::size_t(w) + std::size_t(x)]);
    }
  }
  return sum;
}

}  // namespace relief::test
