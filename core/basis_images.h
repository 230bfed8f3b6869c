// §3 Eq. 2: "the auxiliary function S ... a convex combination of basis functions",
// S(x) = sum_i w_i I_i(x), each I_i a grey-scale image and each w_i a constant or a grey-scale
// weight image. The noise lattice of §2.1 is already such an S: a periodic P x P grid of values,
// interpolated. So the basis images are composed once per scene, texel by texel, into a P x P
// grid that takes the lattice's place in stage 3 (same interpolant, octave offsets, warp, LOD,
// height bounds from its extremes), and every backend carries it unchanged:
//   composed[t] = sum_i w_i[t] I_i[t] / sum_i w_i[t]
// renormalised at every texel (the paper renormalises the weights after each edit), formed in
// double and rounded once to float. The shading's noise (dithering, waves) keeps the lattice.
// docs/terrain-spec.md, section 12, specifies the filters, the wrap and the seam measure.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/lattice.h"
#include "core/scene/scene.h"

namespace relief {

// A square grid of doubles, row-major (values[y * side + x]); a decoded grey image has its
// grey levels mapped to [0, 1].
struct GreyGrid {
  int side = 0;
  std::vector<double> values;

  double at(int x, int y) const { return values[std::size_t(y) * std::size_t(side) + x]; }
};

// The image mirrored into 2W x 2W: out(x, y) = in(m(x), m(y)), m(x) = x for x < W and
// 2W - 1 - x otherwise, so the result repeats seamlessly (C0) whatever the image.
GreyGrid mirror_grid(const GreyGrid& image);

// How badly the image tiles: the RMS of the steps across its wrap (last column to first, last
// row to first: 2W steps) divided by the RMS of the steps between neighbours inside it
// (2W(W - 1) steps). About 1 for an image that tiles, W - 1 for a ramp, 0 for a mirrored
// grid or a constant one. Precondition: side >= 2.
double seam_measure(const GreyGrid& image);

// The scene's filters of one image, in this order (sigmas in texels, periodic:
// periodic_gaussian.h): low_pass, the Gaussian blur; high_pass, the image minus its blur;
// normalize, (v - mean) / standard deviation. Throws SceneError(field) when normalize meets an
// image whose standard deviation is at most kMinBasisDeviation (a constant image: variance 0).
// Precondition: sigmas validated and at most side / 2.
inline constexpr double kMinBasisDeviation = 1e-9;
void filter_basis_image(GreyGrid& image, const BasisImageSettings& settings,
                        const std::string& field);

// One term of Eq. 2: the (filtered, wrapped) image and its weight, a grid of the same side or a
// constant.
struct BasisTerm {
  const GreyGrid* image = nullptr;
  const GreyGrid* weight_image = nullptr;  // null: `weight`
  double weight = 0;
};

// The grid refined `factor` times per side by the periodic uniform cubic B-spline of its
// values: fine texel X sits at coarse coordinate X / factor, and takes the B-spline weights
// (core/height_sketch.h, bspline_weights) of the four coarse texels around it, along x then
// along y, in double. A convex combination, so it stays within the grid's extremes; it
// reproduces constants, and at a coarse texel it is (v[-1] + 4 v[0] + v[1]) / 6 along each
// axis (the spline approximates). Why: every interpolant of stage 3 has zero slope at the
// texels (core/interpolant.h) but the linear one, so a smooth image shows one terrace per
// texel; the refined grid is C2-smooth at the coarse scale and the linear interpolant's kinks
// between its fine texels are `factor`^2 times smaller than over the coarse grid's.
// Precondition: factor >= 1, side >= 1.
GreyGrid bspline_refine(const GreyGrid& grid, int factor);

// The composed grid as a NoiseLattice (seed 0, size P x upsample, extremes set), refined by
// bspline_refine when upsample > 1 and rounded once to float. `source_side`: the side of the
// images before mirroring (P when not mirrored), to name a texel in messages. Throws
// SceneError("terrain.basis.images") naming the texel (x, y) where the weights sum to zero.
// Preconditions: at least one term, every grid of side P a power of two, weights >= 0,
// upsample a power of two with P x upsample <= kMaxLatticeSize.
NoiseLattice compose_basis(std::span<const BasisTerm> terms, int source_side, int upsample = 1);

// The terrain settings stage 3 runs with: with basis images, the composed grid's side P as
// lattice_size and tile_size / P as horizontal_scale; otherwise `terrain` unchanged.
TerrainSettings stage3_terrain(const TerrainSettings& terrain, int grid_side);

}  // namespace relief
