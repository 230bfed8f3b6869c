#include "core/lattice.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

#include "core/counter_hash.h"
#include "core/det_math.h"

namespace relief {

namespace {

// The polar method accepts a pair with probability pi/4; 64 rejections in a row happen with
// probability 3e-43, so the loop bound is a formality that keeps the function total.
constexpr int kMaxPolarAttempts = 64;

}  // namespace

double lattice_normal(std::uint64_t seed, int i, int j) {
  const std::uint64_t cell = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(j)) << 32) |
                             static_cast<std::uint32_t>(i);
  for (int attempt = 0; attempt < kMaxPolarAttempts; ++attempt) {
    const std::uint64_t draw = 2 * static_cast<std::uint64_t>(attempt);
    const double v1 =
        2.0 * unit_open_interval(counter_hash(seed, HashStream::kLattice, cell, draw)) - 1.0;
    const double v2 =
        2.0 * unit_open_interval(counter_hash(seed, HashStream::kLattice, cell, draw + 1)) - 1.0;
    const double s = v1 * v1 + v2 * v2;
    if (s >= 1.0 || s == 0.0) {
      continue;
    }
    // Domain: 0 < s < 1, so log_det(s) < 0 and the radicand -2 ln(s) / s is positive.
    return v1 * std::sqrt(-2.0 * log_det(s) / s);
  }
  return 0.0;
}

NoiseLattice make_noise_lattice(std::uint64_t seed, int size) {
  assert(size > 0 && std::has_single_bit(static_cast<unsigned>(size)));
  NoiseLattice lattice;
  lattice.seed = seed;
  lattice.size = size;
  lattice.mask = size - 1;
  lattice.values.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      lattice.values[static_cast<std::size_t>(j) * size + i] =
          static_cast<float>(lattice_normal(seed, i, j));
    }
  }
  const auto [lo, hi] = std::minmax_element(lattice.values.begin(), lattice.values.end());
  lattice.min_value = *lo;
  lattice.max_value = *hi;
  return lattice;
}

std::uint64_t lattice_hash(const NoiseLattice& lattice) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (float v : lattice.values) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
    const unsigned char bytes[4] = {
        static_cast<unsigned char>(bits), static_cast<unsigned char>(bits >> 8),
        static_cast<unsigned char>(bits >> 16), static_cast<unsigned char>(bits >> 24)};
    hash = fnv1a64(bytes, 4, hash);
  }
  return hash;
}

}  // namespace relief
