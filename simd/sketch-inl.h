// Per-target body of simd/sketch.h: add_sketch and sample_sketch of core/height_sketch.cc on a
// vector of points, a height field's levels of detail included (each lane's level gathered). The clamps are the scalar std::max/std::min as compares and selections in
// their argument order; the 16 taps are gathered; lanes the mask leaves out keep their height.
#if defined(RELIEF_SIMD_SKETCH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SKETCH_INL_H_
#undef RELIEF_SIMD_SKETCH_INL_H_
#else
#define RELIEF_SIMD_SKETCH_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/height_sketch.h"
#include "simd/lattice-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

// std::min(std::max(s, lo), hi): (s < lo ? lo : s), then (hi < v ? hi : v), for floats and
// for int32 lanes alike.
template <class V>
HWY_INLINE V ClampLanes(V s, V lo, V hi) {
  const V low = hn::IfThenElse(hn::Lt(s, lo), lo, s);
  return hn::IfThenElse(hn::Lt(hi, low), hi, low);
}

// bspline_weights (core/height_sketch.h).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void BsplineWeights(D d, V t, V w[4]) {
  const V one = hn::Set(d, 1.0f), three = hn::Set(d, 3.0f), four = hn::Set(d, 4.0f);
  const V six = hn::Set(d, 6.0f);
  const V s = hn::Sub(one, t);
  w[0] = hn::Div(hn::Mul(hn::Mul(s, s), s), six);
  w[1] = hn::Div(hn::Add(hn::Mul(hn::Mul(hn::Sub(hn::Mul(t, three), six), t), t), four), six);
  w[2] = hn::Div(
      hn::Add(hn::Mul(hn::Add(hn::Mul(hn::Sub(three, hn::Mul(t, three)), t), three), t), one), six);
  w[3] = hn::Div(hn::Mul(hn::Mul(t, t), t), six);
}

// One grid of samples as the lanes see it (sample_grid of core/height_sketch.cc): the sketch's
// level 0 in every lane, or a height field's level per lane.
template <class D>
struct LaneGrid {
  hn::Vec<hn::RebindToSigned<D>> width, height, offset;  // samples, and the level's first
  hn::Vec<D> max_x, max_z;                              // width + 1, height + 1
};

// sample_grid at texel coordinates (sx, sz) of the grid g.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SampleGrid(D d, const LaneGrid<D>& g, const float* HWY_RESTRICT heights, V sx, V sz) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V minus_two = hn::Set(d, -2.0f);
  sx = ClampLanes(sx, minus_two, g.max_x);
  sz = ClampLanes(sz, minus_two, g.max_z);
  const V fx = hn::Floor(sx), fz = hn::Floor(sz);
  V wx[4], wz[4];
  BsplineWeights(d, hn::Sub(sx, fx), wx);
  BsplineWeights(d, hn::Sub(sz, fz), wz);
  const VI i = hn::ConvertTo(di, fx);  // in [-2, width + 1]: exact
  const VI j = hn::ConvertTo(di, fz);
  const VI zero = hn::Zero(di), one = hn::Set(di, 1);
  const VI last_i = hn::Sub(g.width, one), last_j = hn::Sub(g.height, one);
  VI column[4];
  for (int k = 0; k < 4; ++k) {
    column[k] = hn::Add(ClampLanes(hn::Add(i, hn::Set(di, k - 1)), zero, last_i), g.offset);
  }
  V sum = hn::Zero(d);
  for (int m = 0; m < 4; ++m) {
    const VI row = hn::Mul(ClampLanes(hn::Add(j, hn::Set(di, m - 1)), zero, last_j), g.width);
    const V r = hn::Add(
        hn::Add(hn::Add(hn::Mul(wx[0], hn::GatherIndex(d, heights, hn::Add(row, column[0]))),
                        hn::Mul(wx[1], hn::GatherIndex(d, heights, hn::Add(row, column[1])))),
                hn::Mul(wx[2], hn::GatherIndex(d, heights, hn::Add(row, column[2])))),
        hn::Mul(wx[3], hn::GatherIndex(d, heights, hn::Add(row, column[3]))));
    sum = m == 0 ? hn::Mul(wz[0], r) : hn::Add(sum, hn::Mul(wz[m], r));
  }
  return sum;
}

// sample_field_level at level 0's texel coordinates (sx, sz), each lane at its own level.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SampleFieldLevel(D d, const SketchParams<float>& c, const float* HWY_RESTRICT heights,
                              hn::Vec<hn::RebindToSigned<D>> level, V sx, V sz) {
  const hn::RebindToSigned<D> di;
  LaneGrid<D> g;
  g.width = hn::GatherIndex(di, c.level_width, level);
  g.height = hn::GatherIndex(di, c.level_height, level);
  g.offset = hn::GatherIndex(di, c.level_offset, level);
  g.max_x = hn::ConvertTo(d, hn::Add(g.width, hn::Set(di, 1)));  // exact
  g.max_z = hn::ConvertTo(d, hn::Add(g.height, hn::Set(di, 1)));
  const V scale = hn::GatherIndex(d, c.level_scale, level);
  return SampleGrid(d, g, heights, hn::Mul(sx, scale), hn::Mul(sz, scale));
}

// One vector of points at dx, dz, height (need: the lanes the mask selects); nu null: level 0
// (or a sketch).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SketchVector(D d, const SketchParams<float>& c, const float* HWY_RESTRICT heights,
                          V dx, V dz, const float* nu, V height, hn::Mask<D> need) {
  const V sx = hn::Add(hn::Set(d, c.offset_x), hn::Mul(dx, hn::Set(d, c.inv_cell_x)));
  const V sz = hn::Add(hn::Set(d, c.offset_z), hn::Mul(dz, hn::Set(d, c.inv_cell_z)));
  const hn::RebindToSigned<D> di;
  if (c.levels <= 1 || nu == nullptr) {
    LaneGrid<D> g;
    g.width = hn::Set(di, c.width);
    g.height = hn::Set(di, c.height);
    g.offset = hn::Zero(di);
    g.max_x = hn::Set(d, c.max_x);
    g.max_z = hn::Set(d, c.max_z);
    return hn::IfThenElse(need, hn::Add(height, SampleGrid(d, g, heights, sx, sz)), height);
  }
  // add_sketch's level of detail: lambda clamped to [0, levels - 1], both levels sampled.
  const V lambda = ClampLanes(hn::Sub(hn::Set(d, c.lod_origin), hn::LoadU(d, nu)), hn::Zero(d),
                              hn::Set(d, float(c.levels - 1)));
  const V floor_lambda = hn::Floor(lambda);
  const V t = hn::Sub(lambda, floor_lambda);
  const auto a = hn::ConvertTo(di, floor_lambda);  // in [0, levels - 1]: exact
  const auto b = hn::Min(hn::Add(a, hn::Set(di, 1)), hn::Set(di, c.levels - 1));
  const V fine = SampleFieldLevel(d, c, heights, a, sx, sz);
  const V coarse = SampleFieldLevel(d, c, heights, b, sx, sz);
  return hn::IfThenElse(need, hn::Add(height, hn::Add(fine, hn::Mul(t, hn::Sub(coarse, fine)))),
                        height);
}

void AddSketch(const SketchParams<float>& c, const float* heights, IndexRange range,
               const float* dx, const float* dz, const float* nu, const std::uint8_t* mask,
               float* height) {
  const hn::ScalableTag<float> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  // Needed lanes from the mask bytes: widened to 32-bit lanes and compared as integers (no
  // float compare against the mask's values).
  const auto needed = [&](const std::uint8_t* m, std::size_t count) {
    HWY_ALIGN std::uint32_t flags[HWY_MAX_BYTES / sizeof(float)] = {};
    for (std::size_t t = 0; t < count; ++t) {
      flags[t] = m == nullptr ? 1u : m[t];
    }
    return hn::RebindMask(d, hn::Lt(hn::Zero(du), hn::Load(du, flags)));
  };
  std::size_t k = range.begin;
  for (; k + lanes <= range.end; k += lanes) {
    const V h = hn::LoadU(d, height + k);
    const V out = SketchVector(d, c, heights, hn::LoadU(d, dx + k), hn::LoadU(d, dz + k),
                               nu == nullptr ? nullptr : nu + k, h,
                               needed(mask == nullptr ? nullptr : mask + k, lanes));
    hn::StoreU(out, d, height + k);
  }
  if (k < range.end) {
    // The last points: a padded vector whose extra lanes are not needed.
    HWY_ALIGN float tail_dx[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_dz[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_height[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_nu[HWY_MAX_BYTES / sizeof(float)] = {};  // 0: a level in range
    const std::size_t count = range.end - k;
    for (std::size_t t = 0; t < count; ++t) {
      tail_dx[t] = dx[k + t];
      tail_dz[t] = dz[k + t];
      tail_height[t] = height[k + t];
      tail_nu[t] = nu == nullptr ? 0.0f : nu[k + t];
    }
    const V out =
        SketchVector(d, c, heights, hn::Load(d, tail_dx), hn::Load(d, tail_dz),
                     nu == nullptr ? nullptr : tail_nu, hn::Load(d, tail_height),
                     needed(mask == nullptr ? nullptr : mask + k, count));
    hn::Store(out, d, tail_height);
    for (std::size_t t = 0; t < count; ++t) {
      height[k + t] = tail_height[t];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
