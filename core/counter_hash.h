// The counter-based hash behind every random number in Relief (docs/architecture.md, Determinism).
// Specified in docs/noise-lattice.md; changing it changes every golden hash.
#pragma once

#include <cstdint>

namespace relief {

// SplitMix64's finaliser (Steele, Lea, Flood 2014): a bijection on 64-bit words with full
// avalanche. All arithmetic is modulo 2^64.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// The golden-ratio increment of SplitMix64; added before each mix so that zero inputs do not
// map to the finaliser's fixed point 0.
inline constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

// Independent random streams drawn from one scene seed.
enum class HashStream : std::uint64_t {
  kLattice = 0,       // noise lattice values: a = (j << 32) | i, b = attempt draw index
  kOctaveOffset = 1,  // per-octave lattice offsets: a = octave index, b = axis (0 x, 1 z)
  kHeightField = 2,   // generated height maps: a = (method << 8) | level, b = point index
};

// counter_hash(seed, stream, a, b) = mix64(mix64(mix64(mix64(seed + g) + stream + g) + a + g)
// + b + g), g = kGoldenGamma. Pure function of its arguments: any thread, any order.
constexpr std::uint64_t counter_hash(std::uint64_t seed, HashStream stream, std::uint64_t a,
                                     std::uint64_t b) {
  std::uint64_t h = mix64(seed + kGoldenGamma);
  h = mix64(h + static_cast<std::uint64_t>(stream) + kGoldenGamma);
  h = mix64(h + a + kGoldenGamma);
  return mix64(h + b + kGoldenGamma);
}

// The top 53 bits as a double in the open interval (0, 1): (k + 1/2) 2^-53, exact.
constexpr double unit_open_interval(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

// FNV-1a over bytes, for golden hashes of specified buffers (the lattice).
constexpr std::uint64_t fnv1a64(const unsigned char* bytes, std::uint64_t count,
                                std::uint64_t hash = 0xcbf29ce484222325ull) {
  for (std::uint64_t k = 0; k < count; ++k) {
    hash = (hash ^ bytes[k]) * 0x100000001b3ull;
  }
  return hash;
}

}  // namespace relief
