// The interpolating cubic B-spline's coefficients (core/field_prefilter.h).
#include "core/field_prefilter.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace relief {

namespace {

// The Thomas algorithm's factors for a system of n rows (n >= 2): row i's pivot's reciprocal
// and the super-diagonal it leaves, the same for every row or column of that length.
struct TridiagonalFactors {
  std::vector<double> inverse_pivot;  // 1 / pivot_i, pivot_i in [2 + sqrt 3, 5]: no zero
};

TridiagonalFactors factor(int n) {
  TridiagonalFactors f;
  f.inverse_pivot.resize(std::size_t(n));
  double pivot = 5.0;  // row 0: c[-1] = c[0] gives 5 c[0] + c[1]
  f.inverse_pivot[0] = 1.0 / pivot;
  for (int i = 1; i < n; ++i) {
    const double diagonal = i == n - 1 ? 5.0 : 4.0;
    pivot = diagonal - f.inverse_pivot[std::size_t(i) - 1];  // sub-diagonal 1 times super 1
    f.inverse_pivot[std::size_t(i)] = 1.0 / pivot;
  }
  return f;
}

// Solves the system for `lanes` interleaved right-hand sides: x[i * lanes + k] holds v[i] of
// lane k on entry and c[i] on exit.
void solve(const TridiagonalFactors& f, std::span<double> x, int n, int lanes) {
  const auto at = [&](int i, int k) -> double& { return x[std::size_t(i) * lanes + k]; };
  for (int k = 0; k < lanes; ++k) {
    at(0, k) = (6.0 * at(0, k)) * f.inverse_pivot[0];
  }
  for (int i = 1; i < n; ++i) {
    const double inverse = f.inverse_pivot[std::size_t(i)];
    for (int k = 0; k < lanes; ++k) {
      at(i, k) = (6.0 * at(i, k) - at(i - 1, k)) * inverse;
    }
  }
  for (int i = n - 2; i >= 0; --i) {  // super-diagonal 1: c[i] = d'[i] - c[i + 1] / pivot_i
    const double inverse = f.inverse_pivot[std::size_t(i)];
    for (int k = 0; k < lanes; ++k) {
      at(i, k) = at(i, k) - inverse * at(i + 1, k);
    }
  }
}

}  // namespace

void interpolating_coefficients(std::span<float> values, int width, int height) {
  const std::size_t w = std::size_t(width);
  // Along x: one row at a time.
  {
    const TridiagonalFactors f = factor(width);
    std::vector<double> row(w);
    for (int j = 0; j < height; ++j) {
      float* v = values.data() + std::size_t(j) * w;
      std::copy(v, v + w, row.begin());
      solve(f, row, width, 1);
      std::transform(row.begin(), row.end(), v, [](double c) { return static_cast<float>(c); });
    }
  }
  // Along z: kColumns columns at a time, interleaved, so that each row's read is contiguous.
  constexpr int kColumns = 16;
  const TridiagonalFactors f = factor(height);
  std::vector<double> block(std::size_t(height) * kColumns);
  for (int i0 = 0; i0 < width; i0 += kColumns) {
    const int lanes = std::min(kColumns, width - i0);
    for (int j = 0; j < height; ++j) {
      const float* v = values.data() + std::size_t(j) * w + std::size_t(i0);
      std::copy(v, v + lanes, block.begin() + std::ptrdiff_t(j) * lanes);
    }
    solve(f, std::span(block).first(std::size_t(height) * lanes), height, lanes);
    for (int j = 0; j < height; ++j) {
      float* v = values.data() + std::size_t(j) * w + std::size_t(i0);
      for (int k = 0; k < lanes; ++k) {
        v[k] = static_cast<float>(block[std::size_t(j) * lanes + k]);
      }
    }
  }
}

}  // namespace relief
