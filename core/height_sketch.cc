#include "core/height_sketch.h"

#include <algorithm>
#include <cmath>

#include "core/field_prefilter.h"
#include "core/interpolant.h"

namespace relief {

namespace {

// One level of block extremes from the texels (block_side kFirstBlockSide) or from the level
// below (twice its side: 2 x 2 of its blocks).
HeightBlockLevel coarser_level(const HeightSketch& sketch, const HeightBlockLevel* finer) {
  HeightBlockLevel level;
  const int step = finer == nullptr ? HeightSketch::kFirstBlockSide : 2;
  const int source_width = finer == nullptr ? sketch.width : finer->width;
  const int source_height = finer == nullptr ? sketch.height : finer->height;
  level.block_side = finer == nullptr ? step : 2 * finer->block_side;
  level.width = (source_width + step - 1) / step;
  level.height = (source_height + step - 1) / step;
  level.lo.resize(std::size_t(level.width) * std::size_t(level.height));
  level.hi.resize(level.lo.size());
  for (int bj = 0; bj < level.height; ++bj) {
    for (int bi = 0; bi < level.width; ++bi) {
      float lo = 0, hi = 0;
      bool first = true;
      for (int j = bj * step; j < std::min((bj + 1) * step, source_height); ++j) {
        for (int i = bi * step; i < std::min((bi + 1) * step, source_width); ++i) {
          const std::size_t k = std::size_t(j) * std::size_t(source_width) + std::size_t(i);
          const float a = finer == nullptr ? sketch.heights[k] : finer->lo[k];
          const float b = finer == nullptr ? sketch.heights[k] : finer->hi[k];
          lo = first ? a : std::min(lo, a);
          hi = first ? b : std::max(hi, b);
          first = false;
        }
      }
      level.lo[std::size_t(bj) * std::size_t(level.width) + std::size_t(bi)] = lo;
      level.hi[std::size_t(bj) * std::size_t(level.width) + std::size_t(bi)] = hi;
    }
  }
  return level;
}

// The extremes and the block levels of sketch.heights.
void finish_height_sketch(HeightSketch& sketch) {
  const auto [lowest, highest] = std::minmax_element(sketch.heights.begin(), sketch.heights.end());
  sketch.min_height = *lowest;
  sketch.max_height = *highest;
  sketch.blocks.clear();
  while (sketch.blocks.empty()
             ? std::max(sketch.width, sketch.height) > HeightSketch::kFirstBlockSide
             : std::max(sketch.blocks.back().width, sketch.blocks.back().height) > 1) {
    sketch.blocks.push_back(
        coarser_level(sketch, sketch.blocks.empty() ? nullptr : &sketch.blocks.back()));
  }
}

}  // namespace

namespace {

// heights[k] = lo + (hi - lo) unit(k) in double, rounded once to float; when asked, replaced by
// the coefficients the B-spline interpolates them with; then the extremes (the coefficients':
// the surface's exact bounds), the blocks and, when asked, the levels of detail (one allocation
// for every level).
template <class Unit>
HeightSketch make_field(const SketchSettings& settings, int width, int height, std::size_t count,
                        Unit unit, bool levels_of_detail, bool interpolating) {
  HeightSketch field;
  field.width = width;
  field.height = height;
  if (levels_of_detail) {
    field.heights.reserve(field_levels_samples(width, height));
  }
  field.heights.resize(count);
  const double lo = settings.height[0], hi = settings.height[1];
  for (std::size_t k = 0; k < count; ++k) {
    field.heights[k] = static_cast<float>(lo + (hi - lo) * unit(k));
  }
  if (interpolating) {
    interpolating_coefficients(field.heights, width, height);
  }
  finish_height_sketch(field);
  if (levels_of_detail) {
    build_field_levels(field);
  }
  return field;
}

}  // namespace

HeightSketch make_height_sketch(const SketchSettings& settings, int width, int height,
                                std::span<const std::uint16_t> grey, int max_grey,
                                bool levels_of_detail, bool interpolating) {
  return make_field(
      settings, width, height, grey.size(),
      [&](std::size_t k) { return double(grey[k]) / double(max_grey); }, levels_of_detail,
      interpolating);
}

HeightSketch make_height_field(const SketchSettings& settings, int width, int height,
                               std::span<const float> values, bool levels_of_detail,
                               bool interpolating) {
  return make_field(
      settings, width, height, values.size(), [&](std::size_t k) { return double(values[k]); },
      levels_of_detail, interpolating);
}

SketchPlan make_sketch_plan(const SketchSettings& settings, const HeightSketch& sketch,
                            double camera_x, double camera_z) {
  const auto& e = sketch_extent(settings, sketch);
  SketchPlan plan;
  plan.enabled = true;
  plan.inv_cell_x = double(sketch.width) / (e[2] - e[0]);  // x1 > x0: validate_scene
  plan.inv_cell_z = double(sketch.height) / (e[3] - e[1]);
  plan.offset_x = (camera_x - e[0]) * plan.inv_cell_x - 0.5;
  plan.offset_z = (camera_z - e[1]) * plan.inv_cell_z - 0.5;
  return plan;
}

template <class Real>
SketchParams<Real> make_sketch_params(const SketchPlan& plan, const HeightSketch* sketch) {
  SketchParams<Real> p;
  if (!plan.enabled || sketch == nullptr) {
    return p;
  }
  p.enabled = 1;
  p.width = sketch->width;
  p.height = sketch->height;
  p.offset_x = Real(plan.offset_x);
  p.offset_z = Real(plan.offset_z);
  p.inv_cell_x = Real(plan.inv_cell_x);
  p.inv_cell_z = Real(plan.inv_cell_z);
  p.max_x = Real(sketch->width + 1);
  p.max_z = Real(sketch->height + 1);
  p.levels = sketch->levels();
  p.lod_origin = Real(p.levels);
  for (int l = 0; l < p.levels; ++l) {
    const bool own = !sketch->level_width.empty();
    p.level_width[l] = own ? sketch->level_width[std::size_t(l)] : sketch->width;
    p.level_height[l] = own ? sketch->level_height[std::size_t(l)] : sketch->height;
    p.level_offset[l] = own ? static_cast<std::int32_t>(sketch->level_offset[std::size_t(l)]) : 0;
    p.level_scale[l] = Real(std::ldexp(1.0, -l));  // exact
  }
  return p;
}

namespace {

// The B-spline of a width x height grid of samples at texel coordinate (sx, sz) (the operations
// of docs/terrain-spec.md section 11), its clamp limits max_x = width + 1, max_z = height + 1.
template <class Real>
Real sample_grid(const float* samples, int width, int height, Real max_x, Real max_z, Real sx,
                 Real sz) {
  // Beyond 2 texels outside the centres every tap is an edge texel already: the clamp changes
  // no value and keeps the integer conversion in range (and +-inf finite).
  sx = std::min(std::max(sx, Real(-2)), max_x);
  sz = std::min(std::max(sz, Real(-2)), max_z);
  const Real fx = std::floor(sx), fz = std::floor(sz);
  Real wx[4], wz[4];
  bspline_weights(sx - fx, wx);
  bspline_weights(sz - fz, wz);
  const int i = static_cast<int>(fx), j = static_cast<int>(fz);
  int column[4];
  for (int k = 0; k < 4; ++k) {
    column[k] = std::min(std::max(i + k - 1, 0), width - 1);  // clamp to the edge
  }
  Real sum = Real(0);
  for (int m = 0; m < 4; ++m) {
    const float* row =
        samples + std::size_t(std::min(std::max(j + m - 1, 0), height - 1)) * std::size_t(width);
    const Real r = ((wx[0] * Real(row[column[0]]) + wx[1] * Real(row[column[1]])) +
                    wx[2] * Real(row[column[2]])) +
                   wx[3] * Real(row[column[3]]);
    sum = m == 0 ? wz[0] * r : sum + wz[m] * r;
  }
  return sum;
}

}  // namespace

template <class Real>
Real sample_sketch(const SketchParams<Real>& c, std::span<const float> heights, Real sx, Real sz) {
  return sample_grid<Real>(heights.data(), c.width, c.height, c.max_x, c.max_z, sx, sz);
}

template <class Real>
Real sample_field_level(const SketchParams<Real>& c, std::span<const float> heights, int level,
                        Real sx, Real sz) {
  const int width = c.level_width[level], height = c.level_height[level];
  const Real scale = c.level_scale[level];
  return sample_grid<Real>(heights.data() + c.level_offset[level], width, height, Real(width + 1),
                           Real(height + 1), sx * scale, sz * scale);
}

template <class Real>
void add_sketch(const SketchParams<Real>& c, std::span<const float> heights, IndexRange range,
                std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                std::span<const std::uint8_t> mask, std::span<Real> height) {
  const bool levels = c.levels > 1 && !nu.empty();
  const Real top = Real(c.levels - 1);
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (!mask.empty() && !mask[k]) {
      continue;  // not evaluated: evaluate_fbm left 0, no consumer reads it
    }
    const Real sx = c.offset_x + dx[k] * c.inv_cell_x;
    const Real sz = c.offset_z + dz[k] * c.inv_cell_z;
    if (!levels) {
      height[k] = height[k] + sample_sketch<Real>(c, heights, sx, sz);
      continue;
    }
    // The level of detail: stage 2's count read as a level, both samples always taken (the
    // blend's bits then never depend on a shortcut).
    const Real lambda = std::min(std::max(c.lod_origin - nu[k], Real(0)), top);
    const Real floor_lambda = std::floor(lambda);
    const Real t = lambda - floor_lambda;
    const int a = static_cast<int>(floor_lambda);
    const int b = std::min(a + 1, c.levels - 1);
    const Real fine = sample_field_level<Real>(c, heights, a, sx, sz);
    const Real coarse = sample_field_level<Real>(c, heights, b, sx, sz);
    height[k] = height[k] + (fine + t * (coarse - fine));
  }
}

namespace {

// Taps floor(s) - 1 .. floor(s) + 2 over texel coordinates s0 .. s1 of a side of `count`
// texels, widened by `margin`, clamped to the edges (coordinates clamped as the stage clamps
// them first).
void tap_range(double s0, double s1, double margin, int count, int& lo, int& hi) {
  const double c0 = std::clamp(s0 - margin, -2.0, count + 1.0);
  const double c1 = std::clamp(s1 + margin, -2.0, count + 1.0);
  lo = std::clamp(static_cast<int>(std::floor(c0)) - 1, 0, count - 1);
  hi = std::clamp(static_cast<int>(std::floor(c1)) + 2, 0, count - 1);
}

constexpr std::int64_t kMaxScan = 4096;

// Extremes of level 0's texels [i0, i1] x [j0, j1]: directly up to kMaxScan of them, beyond
// that the blocks of the finest block level that covers them with at most kMaxScan blocks (a
// superset of the texels, so still a bound), so that the cost does not grow with the field.
SketchRange level0_range(const HeightSketch& sketch, int i0, int i1, int j0, int j1) {
  if (std::int64_t(i1 - i0 + 1) * (j1 - j0 + 1) > kMaxScan) {
    for (const HeightBlockLevel& level : sketch.blocks) {
      const int b0 = i0 / level.block_side, b1 = i1 / level.block_side;
      const int c0 = j0 / level.block_side, c1 = j1 / level.block_side;
      if (std::int64_t(b1 - b0 + 1) * (c1 - c0 + 1) > kMaxScan) {
        continue;
      }
      float lo = level.lo[std::size_t(c0) * std::size_t(level.width) + std::size_t(b0)], hi = lo;
      for (int c = c0; c <= c1; ++c) {
        for (int b = b0; b <= b1; ++b) {
          const std::size_t k = std::size_t(c) * std::size_t(level.width) + std::size_t(b);
          lo = std::min(lo, level.lo[k]);
          hi = std::max(hi, level.hi[k]);
        }
      }
      return {lo, hi};
    }
    return {sketch.min_height, sketch.max_height};  // blocks not built (a hand-made sketch)
  }
  float lo = sketch.heights[std::size_t(j0) * std::size_t(sketch.width) + std::size_t(i0)], hi = lo;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const float v = sketch.heights[std::size_t(j) * std::size_t(sketch.width) + std::size_t(i)];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return {lo, hi};
}

}  // namespace

SketchRange sketch_range(const SketchPlan& plan, const HeightSketch& sketch, double x0, double x1,
                         double z0, double z1) {
  // The texel coordinates the stage can form there, widened for float's rounding of the
  // offset and the product (a thousandth of a texel plus 1e-6 relative, far more than
  // float's 2^-24 relative per operation).
  const double sx0 = plan.offset_x + x0 * plan.inv_cell_x,
               sx1 = plan.offset_x + x1 * plan.inv_cell_x;
  const double sz0 = plan.offset_z + z0 * plan.inv_cell_z,
               sz1 = plan.offset_z + z1 * plan.inv_cell_z;
  const double margin_x = 1e-3 + 1e-6 * (std::abs(plan.offset_x) + std::abs(sx0) + std::abs(sx1));
  const double margin_z = 1e-3 + 1e-6 * (std::abs(plan.offset_z) + std::abs(sz0) + std::abs(sz1));
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  tap_range(sx0, sx1, margin_x, sketch.width, i0, i1);
  tap_range(sz0, sz1, margin_z, sketch.height, j0, j1);
  SketchRange range = level0_range(sketch, i0, i1, j0, j1);
  // A height field's coarser levels (build_field_levels): level l's taps at the coordinates
  // times 2^-l (exact), each level's texels a convex combination the B-spline reads. Their
  // extremes join level 0's: directly where few, else level 0's over every texel they filter
  // (level l's texel i reads level 0 within 2^(l+1) - 2 of 2^l i).
  // The fallback windows of level 0 nest (each level's reaches past the one before): one
  // block scan over the widest of them serves every level that needs it.
  int wide_i0 = sketch.width, wide_i1 = -1, wide_j0 = sketch.height, wide_j1 = -1;
  for (int l = 1; l < sketch.levels(); ++l) {
    const double scale = std::ldexp(1.0, -l);
    const int w = sketch.level_width[std::size_t(l)], h = sketch.level_height[std::size_t(l)];
    int a0 = 0, a1 = 0, c0 = 0, c1 = 0;
    tap_range(sx0 * scale, sx1 * scale, margin_x, w, a0, a1);
    tap_range(sz0 * scale, sz1 * scale, margin_z, h, c0, c1);
    if (std::int64_t(a1 - a0 + 1) * (c1 - c0 + 1) <= kMaxScan) {
      const float* samples = sketch.heights.data() + sketch.level_offset[std::size_t(l)];
      for (int c = c0; c <= c1; ++c) {
        for (int a = a0; a <= a1; ++a) {
          const double v = samples[std::size_t(c) * std::size_t(w) + std::size_t(a)];
          range.lo = std::min(range.lo, v);
          range.hi = std::max(range.hi, v);
        }
      }
      continue;
    }
    const int reach = (2 << l) - 2;
    wide_i0 = std::min(wide_i0, std::clamp((a0 << l) - reach, 0, sketch.width - 1));
    wide_i1 = std::max(wide_i1, std::clamp((a1 << l) + reach, 0, sketch.width - 1));
    wide_j0 = std::min(wide_j0, std::clamp((c0 << l) - reach, 0, sketch.height - 1));
    wide_j1 = std::max(wide_j1, std::clamp((c1 << l) + reach, 0, sketch.height - 1));
  }
  if (wide_i1 >= 0) {
    const SketchRange wide = level0_range(sketch, wide_i0, wide_i1, wide_j0, wide_j1);
    range.lo = std::min(range.lo, wide.lo);
    range.hi = std::max(range.hi, wide.hi);
  }
  return range;
}

template SketchParams<float> make_sketch_params<float>(const SketchPlan&, const HeightSketch*);
template SketchParams<double> make_sketch_params<double>(const SketchPlan&, const HeightSketch*);
template float sample_sketch<float>(const SketchParams<float>&, std::span<const float>, float,
                                    float);
template double sample_sketch<double>(const SketchParams<double>&, std::span<const float>, double,
                                      double);
template float sample_field_level<float>(const SketchParams<float>&, std::span<const float>, int,
                                         float, float);
template double sample_field_level<double>(const SketchParams<double>&, std::span<const float>, int,
                                           double, double);
template void add_sketch<float>(const SketchParams<float>&, std::span<const float>, IndexRange,
                                std::span<const float>, std::span<const float>,
                                std::span<const float>, std::span<const std::uint8_t>,
                                std::span<float>);
template void add_sketch<double>(const SketchParams<double>&, std::span<const float>, IndexRange,
                                 std::span<const double>, std::span<const double>,
                                 std::span<const double>, std::span<const std::uint8_t>,
                                 std::span<double>);

}  // namespace relief
