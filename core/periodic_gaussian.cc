#include "core/periodic_gaussian.h"

#include <bit>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/det_math.h"

namespace relief {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLog2E = 1.4426950408889634;  // 1 / ln 2: e^x = 2^(x log2 e)

struct Complex {
  double re = 0, im = 0;
};

Complex times(Complex a, Complex b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}

// exp(-2 pi i k / n) for k < n / 2. The angle 2 pi / 2^m has cos and sin from the half-angle
// recursion (cos t/2 = sqrt((1 + cos t) / 2), sin t/2 = sin t / (2 cos t/2), from t = pi / 2),
// and e^(-2 pi i k / n) is the product of the angles of k's set bits, lowest bit first.
std::vector<Complex> twiddles(int n) {
  const int bits = std::countr_zero(static_cast<unsigned>(n));
  // unit[b]: angle 2 pi 2^b / n = 2 pi / 2^(bits - b).
  std::vector<Complex> unit(static_cast<std::size_t>(std::max(bits, 1)));
  double c = 0.0, s = 1.0;  // 2 pi / 4
  for (int m = 2; m <= bits; ++m) {
    const int b = bits - m;
    if (m > 2) {
      const double half_cos = std::sqrt((1.0 + c) / 2.0);  // 1 + c > 0: angle < pi
      s = s / (2.0 * half_cos);
      c = half_cos;
    }
    unit[static_cast<std::size_t>(b)] = {c, -s};
  }
  if (bits >= 1) {
    unit[static_cast<std::size_t>(bits - 1)] = {-1.0, 0.0};  // angle pi
  }
  std::vector<Complex> w(static_cast<std::size_t>(std::max(n / 2, 1)));
  for (int k = 0; k < n / 2; ++k) {
    Complex z{1.0, 0.0};
    for (int b = 0; b < bits; ++b) {
      if ((k >> b) & 1) {
        z = times(z, unit[static_cast<std::size_t>(b)]);
      }
    }
    w[static_cast<std::size_t>(k)] = z;
  }
  return w;
}

// In-place radix-2 FFT of n values spaced `stride` apart; inverse: conjugate twiddles (the
// 1 / n is the caller's).
void fft(Complex* data, int n, std::size_t stride, const std::vector<Complex>& w, bool inverse) {
  for (int i = 1, j = 0; i < n; ++i) {
    int bit = n >> 1;
    for (; j & bit; bit >>= 1) {
      j ^= bit;
    }
    j ^= bit;
    if (i < j) {
      std::swap(data[std::size_t(i) * stride], data[std::size_t(j) * stride]);
    }
  }
  for (int len = 2; len <= n; len <<= 1) {
    const int step = n / len;
    for (int start = 0; start < n; start += len) {
      for (int k = 0; k < len / 2; ++k) {
        Complex t = w[std::size_t(k) * std::size_t(step)];
        if (inverse) {
          t.im = -t.im;
        }
        Complex& a = data[std::size_t(start + k) * stride];
        Complex& b = data[std::size_t(start + k + len / 2) * stride];
        const Complex v = times(b, t);
        b = {a.re - v.re, a.im - v.im};
        a = {a.re + v.re, a.im + v.im};
      }
    }
  }
}

}  // namespace

void periodic_gaussian_blur(std::span<double> values, int side, double sigma) {
  assert(side >= 1 && std::has_single_bit(static_cast<unsigned>(side)));
  assert(values.size() == std::size_t(side) * std::size_t(side));
  if (!(sigma > 0.0) || side == 1) {
    return;
  }
  const std::size_t n = static_cast<std::size_t>(side);
  std::vector<Complex> grid(n * n);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    grid[k].re = values[k];
  }
  const std::vector<Complex> w = twiddles(side);
  for (std::size_t row = 0; row < n; ++row) {
    fft(&grid[row * n], side, 1, w, false);
  }
  for (std::size_t col = 0; col < n; ++col) {
    fft(&grid[col], side, n, w, false);
  }
  // The response is separable: g(kx) g(ky), each exp(-2 pi^2 sigma^2 (k' / n)^2).
  std::vector<double> g(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double wrapped = k <= n / 2 ? double(k) : double(k) - double(n);
    const double f = wrapped / double(n);
    g[k] = exp2_det(-2.0 * kPi * kPi * sigma * sigma * f * f * kLog2E);
  }
  // Divided by n^2 for the inverse transform (exact: a power of two).
  const double inv = 1.0 / (double(n) * double(n));
  for (std::size_t y = 0; y < n; ++y) {
    for (std::size_t x = 0; x < n; ++x) {
      const double gain = (g[x] * g[y]) * inv;
      grid[y * n + x].re *= gain;
      grid[y * n + x].im *= gain;
    }
  }
  for (std::size_t col = 0; col < n; ++col) {
    fft(&grid[col], side, n, w, true);
  }
  for (std::size_t row = 0; row < n; ++row) {
    fft(&grid[row * n], side, 1, w, true);
  }
  for (std::size_t k = 0; k < grid.size(); ++k) {
    values[k] = grid[k].re;
  }
}

}  // namespace relief
