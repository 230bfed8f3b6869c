#include "core/heightfield/perlin_field.h"

#include <vector>

#include "core/counter_hash.h"
#include "core/det_math.h"

namespace relief {

namespace {

constexpr double kDiagonal = 0.70710678118654752;  // 1 / sqrt(2)
constexpr double kGradients[8][2] = {{1, 0},
                                     {-1, 0},
                                     {0, 1},
                                     {0, -1},
                                     {kDiagonal, kDiagonal},
                                     {-kDiagonal, kDiagonal},
                                     {kDiagonal, -kDiagonal},
                                     {-kDiagonal, -kDiagonal}};
constexpr std::uint64_t kPerlinMethod = 3;  // after the three subdivisions (subdivision.h)

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

}  // namespace

PeriodicGrid perlin_field(const PerlinSettings& s, const std::function<void(int, int)>& progress) {
  PeriodicGrid g(s.side);
  int octaves = 0;
  for (int cells = s.base_cells; cells <= s.side / 2 && octaves < s.max_octaves; cells *= 2) {
    ++octaves;
  }
  int octave = 0;
  for (int cells = s.base_cells; octave < octaves; cells *= 2, ++octave) {
    const double amplitude = s.amplitude * exp2_det(-double(octave) * s.roughness);
    const int samples = s.side / cells;  // per cell: at least 2
    const auto gradient = [&](int i, int j) {
      const std::uint64_t point =
          std::uint64_t(j % cells) * std::uint64_t(cells) + std::uint64_t(i % cells);
      const std::uint64_t bits = counter_hash(s.seed, HashStream::kHeightField,
                                              (kPerlinMethod << 8) | std::uint64_t(octave), point);
      return kGradients[bits >> 61];
    };
    // The gradients of the lattice rows below and above the current row of samples.
    std::vector<const double*> below(std::size_t(cells) + 1), above(std::size_t(cells) + 1);
    for (int z = 0; z < s.side; ++z) {
      const int j = z / samples;
      if (z % samples == 0) {
        for (int i = 0; i <= cells; ++i) {
          below[std::size_t(i)] = gradient(i, j);
          above[std::size_t(i)] = gradient(i, j + 1);
        }
      }
      const double fz = double(z % samples) / samples;  // exact: samples a power of two
      const double wz = fade(fz);
      for (int x = 0; x < s.side; ++x) {
        const int i = x / samples;
        const double fx = double(x % samples) / samples;
        const double wx = fade(fx);
        const auto dot = [&](const double* grad, int di, int dj) {
          return grad[0] * (fx - di) + grad[1] * (fz - dj);
        };
        const double d00 = dot(below[std::size_t(i)], 0, 0);
        const double d10 = dot(below[std::size_t(i) + 1], 1, 0);
        const double d01 = dot(above[std::size_t(i)], 0, 1);
        const double d11 = dot(above[std::size_t(i) + 1], 1, 1);
        const double bottom = d00 + wx * (d10 - d00);
        const double top = d01 + wx * (d11 - d01);
        const std::size_t at = std::size_t(z) * std::size_t(s.side) + std::size_t(x);
        g.heights[at] =
            static_cast<float>(double(g.heights[at]) + amplitude * (bottom + wz * (top - bottom)));
      }
    }
    if (progress) {
      progress(octave + 1, octaves);
    }
  }
  return g;
}

}  // namespace relief
