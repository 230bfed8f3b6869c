// Random test inputs from the project's counter hash (core/counter_hash.h) instead of <random>'s
// distributions, whose values differ between standard libraries: the same inputs everywhere.
#pragma once

#include <cstdint>

#include "core/counter_hash.h"

namespace relief::test {

// Uniform in [lo, hi) from a counter-based hash of `key` (test inputs only).
inline double hashed_uniform(std::uint64_t key, double lo, double hi) {
  return lo + (hi - lo) * unit_open_interval(mix64(key + kGoldenGamma));
}

// A sequence of such draws: the k-th of stream `seed` is hashed_uniform(mix64(seed) + k, ...).
class HashedDraws {
 public:
  explicit HashedDraws(std::uint64_t seed) : base_(mix64(seed)) {}
  double uniform(double lo, double hi) { return hashed_uniform(base_ + count_++, lo, hi); }

 private:
  std::uint64_t base_;
  std::uint64_t count_ = 0;
};

}  // namespace relief::test
