// Per-target layer weights of stage 8 (core/layer_weights.cc) for simd/shade-inl.h: the
// product of each layer's four ramps, renormalised, with the scalar code's operations in its
// order.
#if defined(RELIEF_SIMD_LAYER_WEIGHTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_LAYER_WEIGHTS_INL_H_
#undef RELIEF_SIMD_LAYER_WEIGHTS_INL_H_
#else
#define RELIEF_SIMD_LAYER_WEIGHTS_INL_H_
#endif

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/stage_params.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// ramp_weight / rising / falling (layer_weights.cc). Returns false for an open ramp (the
// factor is exactly 1 and the product skips it: x * 1 == x bit for bit).
template <class D, class V = hn::Vec<D>>
HWY_INLINE bool RampFactor(D d, const RampParams<float>& ramp, bool falling, V x, V dither_offset,
                           V& factor) {
  if (ramp.open) {
    return false;
  }
  const float start = ramp.start, end = ramp.end;
  V weight;
  if (!(end > start)) {
    weight = hn::IfThenElseZero(hn::Ge(x, hn::Set(d, start)), hn::Set(d, 1.0f));
  } else {
    weight = Smooth01(
        d, hn::Add(hn::Div(hn::Sub(x, hn::Set(d, start)), hn::Set(d, end - start)), dither_offset));
  }
  factor = falling ? hn::Sub(hn::Set(d, 1.0f), weight) : weight;
  return true;
}

// layer_weights (layer_weights.cc): the product of the four ramps per layer, renormalised.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void LayerWeights(D d, const ShadeParams<float>& p, V height, V slope, V dither_offset,
                             V* weights) {
  const int count = p.layer_count;
  V sum = hn::Zero(d);
  for (int k = 0; k < count; ++k) {
    const LayerParams<float>& l = p.layers[k];
    // ((height_up falling(height_down)) slope_up) falling(slope_down), left to right.
    V w = hn::Set(d, 1.0f);
    bool started = false;
    const auto multiply = [&](const RampParams<float>& ramp, bool falling, V x) {
      V factor;
      if (RampFactor(d, ramp, falling, x, dither_offset, factor)) {
        w = started ? hn::Mul(w, factor) : factor;
        started = true;
      }
    };
    multiply(l.height_up, false, height);
    multiply(l.height_down, true, height);
    multiply(l.slope_up, false, slope);
    multiply(l.slope_down, true, slope);
    weights[k] = w;
    sum = hn::Add(sum, w);
  }
  const auto renormalise = hn::Gt(sum, hn::Set(d, float(1e-6)));
  const V inv = hn::Div(hn::Set(d, 1.0f), sum);
  const V share = hn::Set(d, 1.0f / float(count));
  for (int k = 0; k < count; ++k) {
    weights[k] = hn::IfThenElse(renormalise, hn::Mul(weights[k], inv), share);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
