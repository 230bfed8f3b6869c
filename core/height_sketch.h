// §3's low-frequency base: "a coarse sketch of the terrain ... to which the fractal adds the
// fine-scale detail". A grey-scale image over a world rectangle [x0, x1] x [z0, z1], its texels
// holding world heights (black: height[0], white: height[1]), added to the fractal's height in
// stage 3 (docs/terrain-spec.md, section 11).
//
// Interpolation: texel (i, j) sits at its centre, x0 + (i + 1/2) (x1 - x0) / W, z0 + (j + 1/2)
// (z1 - z0) / H (PNG row 0 at z0: the image seen from above with -z up, a map with north up).
// The sketch is the uniform cubic B-spline of the texels (4 x 4 taps, weights bspline_weights):
//   - C2 everywhere, and it reproduces linear ramps exactly, so a sloping sketch gives a
//     uniform slope. (A quintic-weighted bilinear, the lattice's S, is C2 too but has zero
//     gradient at every texel centre: on a coarse sketch's long slopes that shows as terraces,
//     one per texel, which the first renders of the island showed plainly.)
//   - a convex combination of its 16 taps (every weight >= 0): it never leaves [min, max] of
//     the texels it reads, so the height bounds are the texels' extremes, exact (Catmull-Rom,
//     interpolating, overshoots by up to 28% of the step and would need a looser bound).
//   - the price: it approximates rather than interpolates (at a texel centre it is (v_-1 + 4 v_0
//     + v_1) / 6 along each axis), a smoothing of a coarse sketch's steps (an 8-bit sketch's
//     quantisation included) that a low-frequency base wants anyway.
// Outside the rectangle the taps are clamped to the edge texels (GL_CLAMP_TO_EDGE): a sketch
// does not tile; from one texel beyond the edge centres (half a texel outside the rectangle)
// on, it is constant outwards along that axis.
//
// Camera-relative, as the fractal's lattice (docs/architecture.md): the texel coordinate of a
// vertex is offset + d inv_cell, with offset = (C - x0) inv_cell - 1/2 formed once per frame in
// double and rounded once, and inv_cell = W / (x1 - x0); the per-vertex product is small near
// the camera, so a sketch a million units out is as accurate as one at the origin.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/grid_buffers.h"
#include "core/limits.h"
#include "core/scene/scene.h"
#include "core/stage_param_fields.h"

namespace relief {

// The extremes of square blocks of texels, for regional bounds over a large field: level L's
// blocks are kFirstBlockSide 2^L texels a side (the last row and column of blocks cut by the
// field's edge), block (bi, bj) at bj * width + bi.
struct HeightBlockLevel {
  int block_side = 0;         // texels a block spans along each axis
  int width = 0, height = 0;  // blocks along x and z
  std::vector<float> lo, hi;
};

// The texels, decoded once per scene (pipeline/scene_resources.h): §3's sketch or a height
// field (terrain.heightfield), sampled alike.
struct HeightSketch {
  int width = 0;   // texels along x (>= 2)
  int height = 0;  // texels along z (>= 2)
  // World heights, row j (along z) at j * width: lo + (hi - lo) v for the stored value v (a
  // level divided by its maximum, or a PFM's float) formed in double and rounded once to float
  // (both precisions read the same values).
  std::vector<float> heights;
  float min_height = 0, max_height = 0;  // extremes of `heights`
  // Block extremes, coarser level after level, until one block spans the field (none for a
  // field of at most kFirstBlockSide texels a side): sketch_range's regional bounds in time
  // independent of the region's size, for a twelfth of `heights`' memory.
  std::vector<HeightBlockLevel> blocks;
  static constexpr int kFirstBlockSide = 4;
  // A height field's levels of detail (build_field_levels), level 0 the samples themselves:
  // level l's level_width[l] x level_height[l] values follow level l - 1's in `heights`, from
  // level_offset[l]. A sketch has level 0 only.
  std::vector<int> level_width, level_height;
  std::vector<std::size_t> level_offset;
  int levels() const { return level_width.empty() ? 1 : int(level_width.size()); }
  // A georeferenced field's extent from its file (terrain.heightfield.georeferenced,
  // pipeline/geotiff_reference.h), in place of the settings' extent; nullopt: the settings'.
  std::optional<std::array<double, 4>> placed_extent;
};

// The world rectangle the texels cover: the file's placement, or the settings' extent.
inline const std::array<double, 4>& sketch_extent(const SketchSettings& settings,
                                                  const HeightSketch& sketch) {
  return sketch.placed_extent ? *sketch.placed_extent : settings.extent;
}

// Appends the levels of detail of a height field's samples, each the one before filtered by
// the binomial [1 4 6 4 1] / 16 along x, then along z (taps clamped to the edge), and every
// other value kept: level l + 1 value i is level l's filtered value 2i, floor(n / 2) + 1 of
// them for n (the last reaches or passes level l's last sample); while a side still shrinks,
// at most limits::kMaxFieldLevels levels. A convex filter: every level lies within level 0's
// extremes. Its texel centres: level l's texel i sits on level 0's texel 2^l i, so its texel
// coordinate is level 0's times 2^-l, exactly.
void build_field_levels(HeightSketch& field);

// The samples of all the levels build_field_levels makes for a width x height field (level 0's
// included), for memory estimates: under 4/3 of level 0's plus a few rows.
std::size_t field_levels_samples(int width, int height);

// heights[k] = lo + (hi - lo) grey[k] / max_grey; grey has width x height values.
// Precondition: validated settings (lo < hi finite), width, height >= 2, max_grey > 0.
// `levels_of_detail`: also build_field_levels (a height field without the fractal).
// `interpolating`: the heights replaced by the coefficients whose B-spline passes through them
// at every texel centre (core/field_prefilter.h; terrain.heightfield.interpolating), before the
// extremes, blocks and levels are formed from them.
HeightSketch make_height_sketch(const SketchSettings& settings, int width, int height,
                                std::span<const std::uint16_t> grey, int max_grey,
                                bool levels_of_detail = false, bool interpolating = false);

// heights[k] = lo + (hi - lo) values[k] (a float file's samples).
// Precondition: validated settings, width, height >= 2, every value finite and every mapped
// height within +-limits::kMaxBaseHeight (the loader refuses others, naming the sample).
HeightSketch make_height_field(const SketchSettings& settings, int width, int height,
                               std::span<const float> values, bool levels_of_detail = false,
                               bool interpolating = false);

// The frame's sketch values in double (per frame, from the camera position).
struct SketchPlan {
  bool enabled = false;
  double offset_x = 0, offset_z = 0;      // texel coordinate of the camera
  double inv_cell_x = 1, inv_cell_z = 1;  // texels per world unit
};

SketchPlan make_sketch_plan(const SketchSettings& settings, const HeightSketch& sketch,
                            double camera_x, double camera_z);

// Stage 3's sketch parameters, each plan value rounded once to Real (members:
// stage_param_fields.h).
template <class Real>
struct SketchParams {
  RELIEF_DECLARE_FIELDS(RELIEF_SKETCH_PARAMS_FIELDS)
};

// The uniform cubic B-spline's weights of the taps floor(s) - 1 .. floor(s) + 2 at t = s -
// floor(s) in [0, 1), in this operation order (docs/terrain-spec.md, section 11): each is >= 0
// and they sum to 1 (to a few ulps).
template <class Real>
inline void bspline_weights(Real t, Real w[4]) {
  const Real s = Real(1) - t;
  w[0] = ((s * s) * s) / Real(6);
  w[1] = ((((t * Real(3)) - Real(6)) * t) * t + Real(4)) / Real(6);
  w[2] = ((((Real(3) - t * Real(3)) * t + Real(3)) * t) + Real(1)) / Real(6);
  w[3] = ((t * t) * t) / Real(6);
}

template <class Real>
SketchParams<Real> make_sketch_params(const SketchPlan& plan, const HeightSketch* sketch);

// The sketch at texel coordinate (sx, sz) (texel centres at integers). Finite for any non-NaN
// input (infinities clamp to the edges).
template <class Real>
Real sample_sketch(const SketchParams<Real>& c, std::span<const float> heights, Real sx, Real sz);

// Level `level` of a height field at level 0's texel coordinate (sx, sz): sample_sketch's
// operations on that level's samples at (sx, sz) times level_scale[level].
// Precondition: 0 <= level < c.levels.
template <class Real>
Real sample_field_level(const SketchParams<Real>& c, std::span<const float> heights, int level,
                        Real sx, Real sz);

// height[k] = height[k] + sketch at camera-relative (dx[k], dz[k]), for k in range where mask
// is non-zero (empty: everywhere). Run after evaluate_fbm in stage 3 when c.enabled.
// With levels of detail (c.levels > 1) and `nu` given, the vertex reads level
//   lambda = min(max(lod_origin - nu[k], 0), levels - 1),  a = floor(lambda),  t = lambda - a,
//   B = B_a + t (B_b - B_a),  b = min(a + 1, levels - 1)
// (§4.1's geomorphing, between two levels instead of two octaves); `nu` empty: level 0.
// Precondition: finite dx, dz, nu.
template <class Real>
void add_sketch(const SketchParams<Real>& c, std::span<const float> heights, IndexRange range,
                std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                std::span<const std::uint8_t> mask, std::span<Real> height);

// Extremes of the sketch over camera-relative base points dx in [x0, x1], dz in [z0, z1]
// (world heights: the texels the interpolation can read there, exact up to 4096 of them,
// beyond that the extremes of the fewest blocks of one level covering them, at most 4096;
// with a height field's levels of detail, joined by every level's texels read there).
// Precondition: finite, x0 <= x1, z0 <= z1.
struct SketchRange {
  double lo = 0, hi = 0;
};
SketchRange sketch_range(const SketchPlan& plan, const HeightSketch& sketch, double x0, double x1,
                         double z0, double z1);

}  // namespace relief
