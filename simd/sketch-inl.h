// Per-target body of simd/sketch.h: add_sketch and sample_sketch of core/height_sketch.cc on a
// vector of points. The clamps are the scalar std::max/std::min as compares and selections in
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

// sample_sketch at texel coordinates (sx, sz).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SampleSketch(D d, const SketchParams<float>& c, const float* HWY_RESTRICT heights,
                          V sx, V sz) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V minus_two = hn::Set(d, -2.0f);
  sx = ClampLanes(sx, minus_two, hn::Set(d, c.max_x));
  sz = ClampLanes(sz, minus_two, hn::Set(d, c.max_z));
  const V fx = hn::Floor(sx), fz = hn::Floor(sz);
  V wx[4], wz[4];
  BsplineWeights(d, hn::Sub(sx, fx), wx);
  BsplineWeights(d, hn::Sub(sz, fz), wz);
  const VI i = hn::ConvertTo(di, fx);  // in [-2, width + 1]: exact
  const VI j = hn::ConvertTo(di, fz);
  const VI zero = hn::Zero(di);
  const VI last_i = hn::Set(di, c.width - 1), last_j = hn::Set(di, c.height - 1);
  const VI width = hn::Set(di, c.width);
  VI column[4];
  for (int k = 0; k < 4; ++k) {
    column[k] = ClampLanes(hn::Add(i, hn::Set(di, k - 1)), zero, last_i);
  }
  V sum = hn::Zero(d);
  for (int m = 0; m < 4; ++m) {
    const VI row = hn::Mul(ClampLanes(hn::Add(j, hn::Set(di, m - 1)), zero, last_j), width);
    const V r = hn::Add(
        hn::Add(hn::Add(hn::Mul(wx[0], hn::GatherIndex(d, heights, hn::Add(row, column[0]))),
                        hn::Mul(wx[1], hn::GatherIndex(d, heights, hn::Add(row, column[1])))),
                hn::Mul(wx[2], hn::GatherIndex(d, heights, hn::Add(row, column[2])))),
        hn::Mul(wx[3], hn::GatherIndex(d, heights, hn::Add(row, column[3]))));
    sum = m == 0 ? hn::Mul(wz[0], r) : hn::Add(sum, hn::Mul(wz[m], r));
  }
  return sum;
}

// One vector of points at dx, dz, height (need: the lanes the mask selects).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SketchVector(D d, const SketchParams<float>& c, const float* HWY_RESTRICT heights,
                          V dx, V dz, V height, hn::Mask<D> need) {
  const V sx = hn::Add(hn::Set(d, c.offset_x), hn::Mul(dx, hn::Set(d, c.inv_cell_x)));
  const V sz = hn::Add(hn::Set(d, c.offset_z), hn::Mul(dz, hn::Set(d, c.inv_cell_z)));
  return hn::IfThenElse(need, hn::Add(height, SampleSketch(d, c, heights, sx, sz)), height);
}

void AddSketch(const SketchParams<float>& c, const float* heights, IndexRange range,
               const float* dx, const float* dz, const std::uint8_t* mask, float* height) {
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
    const V out = SketchVector(d, c, heights, hn::LoadU(d, dx + k), hn::LoadU(d, dz + k), h,
                               needed(mask == nullptr ? nullptr : mask + k, lanes));
    hn::StoreU(out, d, height + k);
  }
  if (k < range.end) {
    // The last points: a padded vector whose extra lanes are not needed.
    HWY_ALIGN float tail_dx[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_dz[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_height[HWY_MAX_BYTES / sizeof(float)] = {};
    const std::size_t count = range.end - k;
    for (std::size_t t = 0; t < count; ++t) {
      tail_dx[t] = dx[k + t];
      tail_dz[t] = dz[k + t];
      tail_height[t] = height[k + t];
    }
    const V out =
        SketchVector(d, c, heights, hn::Load(d, tail_dx), hn::Load(d, tail_dz),
                     hn::Load(d, tail_height), needed(mask == nullptr ? nullptr : mask + k, count));
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
