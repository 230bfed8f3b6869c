#include "core/layer_weights.h"

#include "core/vec3.h"

namespace relief {

namespace {

template <class Real>
Real ramp_weight(const RampParams<Real>& ramp, Real x, Real dither_offset) {
  const Real start = ramp.start, end = ramp.end;
  if (!(end > start)) {
    return x >= start ? Real(1) : Real(0);  // no spread: a step (division domain: end > start)
  }
  return smooth01((x - start) / (end - start) + dither_offset);
}

// An open ramp (a range reaching the end of the domain) does not limit the layer.
template <class Real>
Real rising(const RampParams<Real>& ramp, Real x, Real dither_offset) {
  return ramp.open ? Real(1) : ramp_weight(ramp, x, dither_offset);
}

template <class Real>
Real falling(const RampParams<Real>& ramp, Real x, Real dither_offset) {
  return ramp.open ? Real(1) : Real(1) - ramp_weight(ramp, x, dither_offset);
}

}  // namespace

template <class Real>
void layer_weights(const ShadeParams<Real>& p, Real height, Real slope, Real dither_offset,
                   Real weights[limits::kMaxMaterialLayers]) {
  const std::size_t count = static_cast<std::size_t>(p.layer_count);
  Real sum = Real(0);
  for (std::size_t k = 0; k < count; ++k) {
    const LayerParams<Real>& l = p.layers[k];
    const Real w =
        rising(l.height_up, height, dither_offset) * falling(l.height_down, height, dither_offset) *
        rising(l.slope_up, slope, dither_offset) * falling(l.slope_down, slope, dither_offset);
    weights[k] = w;
    sum = sum + w;
  }
  // Renormalisation; below 1e-6 the layers leave a gap and share equally (division domain).
  if (sum > Real(1e-6)) {
    const Real inv = Real(1) / sum;
    for (std::size_t k = 0; k < count; ++k) {
      weights[k] = weights[k] * inv;
    }
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      weights[k] = Real(1) / Real(count);
    }
  }
}

template void layer_weights<float>(const ShadeParams<float>&, float, float, float, float*);
template void layer_weights<double>(const ShadeParams<double>&, double, double, double, double*);

}  // namespace relief
