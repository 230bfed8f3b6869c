// fBm that tiles over a square texture (core/texture_synthesis.cc's built-in textures).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/counter_hash.h"
#include "core/interpolant.h"
#include "core/lattice.h"

namespace relief {

// fBm that tiles over the texture: octave o uses a lattice of (first_cells << o) cells across
// the texture, so each octave repeats exactly once per texture. Values have a standard
// deviation of about 1.
class TilingNoise {
 public:
  TilingNoise(std::uint64_t seed, int texture_size, int first_cells, int octaves, double gain)
      : size_(texture_size), gain_(gain) {
    for (int o = 0; o < octaves; ++o) {
      const int cells = std::min(first_cells << o, texture_size);
      lattices_.push_back(make_noise_lattice(mix64(seed + std::uint64_t(o)), cells));
      // The texel centres' cells and fade weights along one axis: sample_lattice locates x and
      // z alike, each from its own coordinate, so a texel's four corners and two weights are
      // its column's and its row's entries, the same values it computes per sample.
      const NoiseLattice& l = lattices_.back();
      const double scale = double(l.size) / size_;
      std::vector<AxisCell> axis(static_cast<std::size_t>(texture_size));
      for (int i = 0; i < texture_size; ++i) {
        const double p = (i + 0.5) * scale;
        const LatticeCell<double> c = locate_cell(l, p, p);
        axis[std::size_t(i)] = {c.i0, c.i1, fade<Interpolant::kQuintic>(c.fx)};
      }
      axes_.push_back(std::move(axis));
    }
    double norm = 0, a = 1;
    for (int o = 0; o < octaves; ++o, a *= gain) {
      norm += a * a;
    }
    normalisation_ = 1.0 / std::sqrt(norm);
  }

  // The sum of the octaves' sample_lattice<kQuintic, double> at texel centre (i, j), each
  // octave's corners and weights taken from the axis tables: the same operations in the same
  // order, so the same bits, without locating any cell per texel.
  double operator()(int i, int j) const {
    double sum = 0, amplitude = 1;
    for (std::size_t o = 0; o < lattices_.size(); ++o) {
      const NoiseLattice& l = lattices_[o];
      const AxisCell& x = axes_[o][std::size_t(i)];
      const AxisCell& z = axes_[o][std::size_t(j)];
      const double v00 = l.at(x.c0, z.c0), v10 = l.at(x.c1, z.c0);
      const double v01 = l.at(x.c0, z.c1), v11 = l.at(x.c1, z.c1);
      const double bottom = v00 + x.t * (v10 - v00);
      const double top = v01 + x.t * (v11 - v01);
      sum += amplitude * (bottom + z.t * (top - bottom));
      amplitude *= gain_;
    }
    return sum * normalisation_;
  }

  const std::vector<NoiseLattice>& lattices() const { return lattices_; }

 private:
  struct AxisCell {
    int c0, c1;  // the cell's two lattice indices along the axis
    double t;    // the quintic fade of the position inside it
  };
  int size_;
  double gain_;
  double normalisation_ = 1;
  std::vector<NoiseLattice> lattices_;
  std::vector<std::vector<AxisCell>> axes_;  // per octave, per texel index
};

}  // namespace relief
