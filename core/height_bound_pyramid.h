// The terrain's height bounded per region of the base domain (§4.1: "the maximum height of the
// terrain needs to be known a priori"), so that the projector can leave out ground that no
// terrain there can lift into view (projector.h; docs/paper-reading.md, "§4.1: the projector").
//
// Octave n of Eq. 1 samples S, the interpolated lattice: inside a lattice cell a bilinear
// function of the fades (fade(fx), fade(fz)), a convex combination of the cell's four corner
// values (interpolant.h). Over a region, octave n's sample points cover a rectangle of its
// lattice coordinates, and S's extremes over it are
//   - exact where the rectangle spans at most kExactCells cells per axis (the coarse octaves,
//     which carry most of the amplitude): the fades are monotone and a bilinear function is
//     linear along each axis, so over the rectangle's piece in each cell S is extreme at the
//     piece's corners: S at the rectangle's corners, where its sides cross lattice lines and
//     at the lattice points inside it bounds S over the rectangle;
//   - otherwise within [min, max] of the lattice values with indices floor(p_lo) ..
//     floor(p_hi) + 1 on each axis (taken modulo P: the lattice is periodic), from a min and a
//     max pyramid of the lattice (level l: the extremes of 2^l x 2^l aligned blocks) with at
//     most 3 x 3 texel reads; a rectangle of P cells or more gets the global extremes.
// §4.1's LOD sums floor(nu) octaves and weights the next by nu - floor(nu): the height lies
// between two consecutive partial sums P_m = sum_{n < m} a_n S_n (m = floor(nu) >= 1, since nu
// >= 1), so within the lowest and the highest partial sum of the octaves' bounds,
//   min_m sum_{n < m} a_n S_lo,n  <=  fBm  <=  max_m sum_{n < m} a_n S_hi,n.
// Each octave's extremes lie within the lattice's, so the regional bound is never wider than
// global(), the bound of height_bounds.h; a region touching all of an octave's lattice gets that
// octave's global extremes.
//
// §2.2 domain warping moves octave n's sample point by W_n (fbm.h). It is bounded rigorously
// rather than falling back to the global slab, because its first octaves, which carry most of
// the amplitude, are the ones it moves least: W_k0 = t0 exactly, and after octave n
//   |W_n+1| <= r (|W_n| + |c3| |h_n| max |R / (R^2 + eps^2)|),   R = R0 - h_n,
// since Rot is a rotation (a unit vector, renormalised or kept). The stage updates W only
// while every LOD weight so far is 1, so h_n is the partial sum through octave n, which the
// region's own bound holds: |h_n| <= max(|lo_n|, |hi_n|), and the guarded inverse is largest
// (1 / (2 eps) at |R| = eps) at an end of R's interval or at +-eps inside it. Octave n's
// rectangle is widened by that radius (its own lattice cells) on every side. The radius grows
// like r^n in octave n's own cells, so the fine octaves of a warped terrain get their global
// extremes, the coarse ones stay regional.
//
// §3's sketch (height_sketch.h) adds the extremes of the texels the region's points can read
// (a region spanning more than 4096 texels gets the sketch's global extremes).
//
// Float: the stage forms p = offset + f u + W in float (fbm.cc) and rounds each interpolation
// step; the rectangle is widened by kHeightBoundSlack of the coordinates' magnitude (a thousand
// times float's rounding) and the heights by kHeightBoundSlack of their magnitude, as
// height_bounds.h does. The bound holds for the float and the double stage, at any nu.
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_plan.h"
#include "core/lattice.h"

namespace relief {

// Extremes of the lattice values over aligned blocks: level l holds (P >> l)^2 texels, texel
// (I, J) the min and max of the values with indices in [I 2^l, (I + 1) 2^l) x [J 2^l, ...).
// Levels below first_level are not stored (lattices above 512^2: at most 256^2 texels on the
// finest stored level, so the pyramid stays below 0.7 MB); ranges of at most kDirectScanValues
// lattice values are read from the lattice itself.
struct LatticeRangePyramid {
  int size = 0;                           // P
  int log2_size = 0;                      // the top level: one texel, the whole lattice
  int first_level = 1;                    // the finest level stored
  std::vector<std::size_t> level_offset;  // into lo and hi, by level
  std::vector<float> lo, hi;
  float global_lo = 0, global_hi = 0;
};

LatticeRangePyramid make_lattice_range_pyramid(const NoiseLattice& lattice);

struct ValueRange {
  double lo = 0;
  double hi = 0;
};

// Min and max of the lattice values with indices i in [i0, i0 + ni), j in [j0, j0 + nj), taken
// modulo P. Precondition: 1 <= ni, nj; ranges of P or more get the global extremes.
ValueRange lattice_range(const LatticeRangePyramid& pyramid, const NoiseLattice& lattice,
                         std::int64_t i0, std::int64_t ni, std::int64_t j0, std::int64_t nj);

// A world-space region's height bound, per frame: the octave table, warp and lattice of one
// TerrainPlan (whose lattice must outlive this object, as the pyramid must).
class RegionalHeightBound {
 public:
  RegionalHeightBound(const TerrainPlan& terrain, const LatticeRangePyramid& pyramid);

  // Camera-relative heights (world units) that stage 3 can produce, in float or in double and
  // for any octave count nu in [1, N], at every camera-relative base point (dx, dz) with
  // dx in [x0, x1], dz in [z0, z1]. Precondition: finite, x0 <= x1, z0 <= z1.
  ValueRange bound(double x0, double x1, double z0, double z1) const;

  // The same with every octave at its global extremes: the widest the bound can be.
  ValueRange global() const;

 private:
  // The extremes of octave n's S over the sample points of the box, its warp displacement
  // within `radius` (lattice cells of octave n).
  ValueRange octave_range(int n, double radius, double x0, double x1, double z0, double z1) const;
  // The fractal's bound plus §3's sketch over the box (height_sketch.h), when there is one.
  ValueRange with_sketch(ValueRange fractal, double x0, double x1, double z0, double z1) const;

  const TerrainPlan& terrain_;
  const LatticeRangePyramid& pyramid_;
  double fbm_slack_ = 0;     // float's rounding of a partial sum, dimensionless
  double height_slack_ = 0;  // and of a height, world units
};

}  // namespace relief
