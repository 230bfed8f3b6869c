#include <cmath>
#include <cstdint>

#include <catch2/catch.hpp>

#include "core/counter_hash.h"
#include "core/lattice.h"

namespace relief {
namespace {

// The values below are part of the lattice specification (docs/noise-lattice.md): a change
// of the hash, the polar method, log_det or the float rounding changes them, and with them
// every terrain Relief has ever rendered. They are not snapshots of incidental output.
TEST_CASE("counterHashMatchesItsSpecifiedTestVectors", "[lattice]") {
  CHECK(mix64(0) == 0);
  CHECK(mix64(kGoldenGamma) == 0xe220a8397b1dcdafull);  // SplitMix64's first output for seed 0
  CHECK(counter_hash(1, HashStream::kLattice, 0, 0) == 0xe28195ddd9ee4956ull);
  CHECK(counter_hash(1, HashStream::kOctaveOffset, 3, 1) == 0xcc6cf1ac9cc23bafull);
}

TEST_CASE("latticeOfSeedOneHasItsGoldenHash", "[lattice]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  CHECK(lattice_hash(lattice) == 0x571ca9ae9509567aull);
}

TEST_CASE("latticeValuesAreTheSpecifiedNormalsRoundedToFloat", "[lattice]") {
  const NoiseLattice lattice = make_noise_lattice(42, 16);
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      CHECK(lattice.at(i, j) == static_cast<float>(lattice_normal(42, i, j)));
    }
  }
}

TEST_CASE("latticeSampleMeanAndVarianceAreThoseOfAStandardNormal", "[lattice]") {
  for (std::uint64_t seed : {1ull, 2ull, 12345ull}) {
    const NoiseLattice lattice = make_noise_lattice(seed, 256);
    const double n = static_cast<double>(lattice.values.size());
    double sum = 0, sum_sq = 0, within_one = 0;
    for (float v : lattice.values) {
      sum += v;
      sum_sq += static_cast<double>(v) * v;
      within_one += std::abs(v) < 1.0f;
    }
    const double mean = sum / n;
    const double variance = sum_sq / n - mean * mean;
    // Five standard errors: 1/sqrt(n) for the mean, sqrt(2/n) for the variance,
    // sqrt(p(1-p)/n) for the fraction within one sigma (p = 0.6827).
    CHECK(std::abs(mean) < 5.0 / std::sqrt(n));
    CHECK(std::abs(variance - 1.0) < 5.0 * std::sqrt(2.0 / n));
    CHECK(std::abs(within_one / n - 0.682689) < 5.0 * std::sqrt(0.6827 * 0.3173 / n));
  }
}

TEST_CASE("latticeDependsOnTheSeedAndRecordsItsExtremes", "[lattice]") {
  const NoiseLattice a = make_noise_lattice(1, 64);
  const NoiseLattice b = make_noise_lattice(2, 64);
  int same = 0;
  for (std::size_t k = 0; k < a.values.size(); ++k) {
    same += a.values[k] == b.values[k];
    CHECK(a.values[k] >= a.min_value);
    CHECK(a.values[k] <= a.max_value);
  }
  CHECK(same < 4);
  CHECK(a.min_value < -2.5f);
  CHECK(a.max_value > 2.5f);
}

}  // namespace
}  // namespace relief
