// The noise lattice of §2.1: a periodic P x P grid of N(0,1) values, a pure function of
// (seed, i, j) through counter_hash, so it is bit-identical on every machine and can be
// uploaded unchanged to a GPU. The specification is docs/noise-lattice.md.
#pragma once

#include <cstdint>
#include <vector>

namespace relief {

struct NoiseLattice {
  std::uint64_t seed = 0;
  int size = 0;               // P, a power of two
  int mask = 0;               // P - 1: the periodic wrap of an index
  std::vector<float> values;  // row-major, values[j * P + i]
  float min_value = 0;        // extremes of values: the interpolants stay inside them,
  float max_value = 0;        // which is what bounds the fBm (height_bounds.h)

  float at(int i, int j) const { return values[static_cast<std::size_t>(j) * size + i]; }
};

// The lattice value at (i, j) in double, before rounding to float: one N(0,1) sample from
// Marsaglia's polar method with counter_hash uniforms and log_det.
double lattice_normal(std::uint64_t seed, int i, int j);

// Builds the P x P lattice. Precondition: size is a power of two in the limits.h range.
NoiseLattice make_noise_lattice(std::uint64_t seed, int size);

// FNV-1a 64 of the values' little-endian IEEE-754 bytes in row-major order.
std::uint64_t lattice_hash(const NoiseLattice& lattice);

}  // namespace relief
