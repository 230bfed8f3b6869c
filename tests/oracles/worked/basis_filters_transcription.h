// Section 12's low_pass and normalize filters re-implemented from the text of
// docs/terrain-spec.md ("The periodic Gaussian, operation by operation": twiddles, FFT, blur;
// step 3's normalize: the row-major mean and standard deviation), not from the code:
// tests/oracles/worked/worked_numbers.cc traces them to print that section's worked numbers
// and compares them bit for bit with relief::periodic_gaussian_blur and
// relief::filter_basis_image.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <utility>
#include <vector>

#include "tests/oracles/worked/det_math_transcription.h"

namespace relief::test::worked {

struct Complex {
  double re, im;
};
// a * b = (a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re)
inline Complex mul(Complex a, Complex b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}

// w[k] = exp(-2pii k / n), k < n/2, from square roots only (the half-angle recursion).
inline std::vector<Complex> spec_twiddles(int n, bool trace) {
  const int bits = std::countr_zero(unsigned(n));
  std::vector<Complex> unit(std::size_t(std::max(bits, 1)));
  double c = 0.0, s = 1.0;  // the angle pi/2
  for (int m = 2; m <= bits; ++m) {
    if (m > 2) {
      const double h = std::sqrt((1.0 + c) / 2.0);
      s = s / (2.0 * h);
      c = h;
    }
    unit[std::size_t(bits - m)] = {c, -s};
  }
  if (bits >= 1)
    unit[std::size_t(bits - 1)] = {-1.0, 0.0};
  if (trace) {
    for (int b = 0; b < bits; ++b) {
      std::printf("  unit[%d] (angle 2pi*%d/%d): %.17g %.17g\n", b, 1 << b, n,
                  unit[std::size_t(b)].re, unit[std::size_t(b)].im);
    }
  }
  std::vector<Complex> w(std::size_t(std::max(n / 2, 1)));
  for (int k = 0; k < n / 2; ++k) {
    Complex z{1.0, 0.0};
    for (int b = 0; b < bits; ++b)
      if ((k >> b) & 1)
        z = mul(z, unit[std::size_t(b)]);
    w[std::size_t(k)] = z;
  }
  return w;
}

// Radix 2, decimation in time, over d[0], d[stride], ..., d[(n - 1) * stride].
inline void spec_fft(Complex* d, int n, std::size_t stride, const std::vector<Complex>& w,
                     bool inverse) {
  for (int i = 0; i < n; ++i) {  // the bit-reversal permutation
    int j = 0;
    for (int b = 1, r = n >> 1; b < n; b <<= 1, r >>= 1)
      if (i & b)
        j |= r;
    if (i < j)
      std::swap(d[std::size_t(i) * stride], d[std::size_t(j) * stride]);
  }
  for (int len = 2; len <= n; len <<= 1) {
    for (int start = 0; start < n; start += len) {
      for (int k = 0; k < len / 2; ++k) {
        Complex t = w[std::size_t(k * (n / len))];
        if (inverse)
          t.im = -t.im;
        Complex& a = d[std::size_t(start + k) * stride];
        Complex& b = d[std::size_t(start + k + len / 2) * stride];
        const Complex v = mul(b, t);
        b = {a.re - v.re, a.im - v.im};
        a = {a.re + v.re, a.im + v.im};
      }
    }
  }
}

// g[k] = exp2_det(-2 * pi * pi * sigma * sigma * f * f * log2 e), f = k' / n.
inline std::vector<double> spec_response(int n, double sigma) {
  const double pi = 3.14159265358979323846, log2e = 1.4426950408889634;
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double f = (k <= n / 2 ? double(k) : double(k) - double(n)) / double(n);
    g[std::size_t(k)] = spec_exp2<double>(-2.0 * pi * pi * sigma * sigma * f * f * log2e, false);
  }
  return g;
}

inline void spec_blur(std::vector<double>& v, int n, double sigma) {
  if (!(sigma > 0.0) || n == 1)
    return;
  const std::size_t side = std::size_t(n);
  std::vector<Complex> g(side * side);
  for (std::size_t k = 0; k < g.size(); ++k)
    g[k] = {v[k], 0.0};
  const std::vector<Complex> w = spec_twiddles(n, false);
  for (std::size_t y = 0; y < side; ++y)
    spec_fft(&g[y * side], n, 1, w, false);
  for (std::size_t x = 0; x < side; ++x)
    spec_fft(&g[x], n, side, w, false);
  const std::vector<double> r = spec_response(n, sigma);
  const double inv = 1.0 / (double(n) * double(n));
  for (std::size_t y = 0; y < side; ++y)
    for (std::size_t x = 0; x < side; ++x) {
      const double gain = (r[x] * r[y]) * inv;
      g[y * side + x].re *= gain;
      g[y * side + x].im *= gain;
    }
  for (std::size_t x = 0; x < side; ++x)
    spec_fft(&g[x], n, side, w, true);
  for (std::size_t y = 0; y < side; ++y)
    spec_fft(&g[y * side], n, 1, w, true);
  for (std::size_t k = 0; k < g.size(); ++k)
    v[k] = g[k].re;
}

// normalize's mean and population standard deviation, summed row by row (y outer, x inner)
// as specified, or column by column (the order the docs show to change the bits).
struct Moments {
  double mean, sd;
};
inline Moments spec_moments(const std::vector<double>& v, int n, bool row_major) {
  const std::size_t side = std::size_t(n);
  auto at = [&](std::size_t outer, std::size_t inner) {
    return row_major ? v[outer * side + inner] : v[inner * side + outer];
  };
  double sum = 0;
  for (std::size_t i = 0; i < side; ++i)
    for (std::size_t j = 0; j < side; ++j)
      sum += at(i, j);
  const double mean = sum / double(n * n);
  double squares = 0;
  for (std::size_t i = 0; i < side; ++i)
    for (std::size_t j = 0; j < side; ++j)
      squares += (at(i, j) - mean) * (at(i, j) - mean);
  return {mean, std::sqrt(squares / double(n * n))};
}

}  // namespace relief::test::worked
