// TilingNoise (core/tiling_noise.h) against its definition: the octaves' sample_lattice at
// each texel centre, located per sample, summed with the gains and normalised; bit for bit.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/interpolant.h"
#include "core/tiling_noise.h"

namespace relief {
namespace {

double defined(const TilingNoise& noise, int size, double gain, int i, int j) {
  double sum = 0, amplitude = 1, norm = 0;
  for (const NoiseLattice& l : noise.lattices()) {
    const double scale = double(l.size) / size;
    sum += amplitude *
           sample_lattice<double>(l, Interpolant::kQuintic, (i + 0.5) * scale, (j + 0.5) * scale);
    norm += amplitude * amplitude;
    amplitude *= gain;
  }
  return sum * (1.0 / std::sqrt(norm));
}

TEST_CASE("tilingNoiseIsTheSumOfItsOctavesSampledPerTexel", "[texture]") {
  struct Case {
    int size, first_cells, octaves;
    double gain;
  };
  for (const Case c : {Case{4, 2, 3, 0.5}, Case{64, 4, 4, 0.55}, Case{256, 8, 3, 0.6},
                       Case{32, 16, 2, 0.5}, Case{128, 2, 5, 0.7}}) {
    const TilingNoise noise(1234 + std::uint64_t(c.size), c.size, c.first_cells, c.octaves, c.gain);
    int differing = 0;
    for (int j = 0; j < c.size; ++j) {
      for (int i = 0; i < c.size; ++i) {
        differing += noise(i, j) != defined(noise, c.size, c.gain, i, j);
      }
    }
    INFO("size " << c.size << ", " << c.octaves << " octaves from " << c.first_cells << " cells");
    CHECK(differing == 0);
    CHECK(noise.lattices().size() == std::size_t(c.octaves));
  }
}

}  // namespace
}  // namespace relief
