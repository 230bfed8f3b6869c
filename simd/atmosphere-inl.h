// Per-target atmosphere of core/atmosphere.cc for float, one direction per lane: the closed
// form of the air's single scattering with the scalar code's operations in its order; phi's
// series and quotient both formed and selected by the scalar branch's test (a lane's unused
// quotient may be 0 / 0: discarded).
// Included by sky-inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_ATMOSPHERE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_ATMOSPHERE_INL_H_
#undef RELIEF_SIMD_ATMOSPHERE_INL_H_
#else
#define RELIEF_SIMD_ATMOSPHERE_INL_H_
#endif

#include <hwy/highway.h>

#include "core/atmosphere.h"
#include "core/limits.h"
#include "core/stage_params.h"
#include "simd/det_math-inl.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// column_growth (atmosphere.cc): phi(z) given e = e^-z.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ColumnGrowth(D d, V z, V e) {
  const V one = hn::Set(d, 1.0f);
  V series = hn::Set(d, float(kGrowthSeries[kGrowthTerms - 1]));
  for (int k = kGrowthTerms - 2; k >= 0; --k) {
    series = hn::Add(hn::Set(d, float(kGrowthSeries[k])), hn::Mul(z, series));
  }
  const V quotient = hn::Div(hn::Sub(one, e), z);
  return hn::IfThenElse(hn::Lt(hn::Abs(z), hn::Set(d, float(kGrowthSeriesLimit))), series,
                        quotient);
}

// One channel of scatter (atmosphere.cc): the in-scattered light, and the transmittance where
// kTransmittance.
template <bool kTransmittance, class D, class V = hn::Vec<D>>
HWY_INLINE void ScatterChannel(D d, float extinction, float camera_sun, float rayleigh, float mie,
                               V one_plus_c2, V mie_phase, V column, V end_sun_column,
                               V& transmittance, V& inscatter) {
  const V view = hn::Mul(hn::Set(d, extinction), column);
  if (kTransmittance) {
    transmittance = Exp2Det(d, hn::Neg(view));
  }
  const V a = hn::Set(d, camera_sun);
  const V b = hn::Add(view, hn::Mul(hn::Set(d, extinction), end_sun_column));
  const V z = hn::Abs(hn::Sub(a, b));
  const V growth = ColumnGrowth(d, hn::Mul(z, hn::Set(d, float(kLn2))), Exp2Det(d, hn::Neg(z)));
  const V integral = hn::Mul(Exp2Det(d, hn::Neg(StdMin(a, b))), hn::Mul(column, growth));
  const V weight =
      hn::Add(hn::Mul(hn::Set(d, rayleigh), one_plus_c2), hn::Mul(hn::Set(d, mie), mie_phase));
  inscatter = hn::Mul(weight, integral);
}

template <bool kTransmittance, class D, class V = hn::Vec<D>>
HWY_INLINE void Scatter(D d, const ShadeParams<float>& p, const V3<V>& dir, V column,
                        V end_sun_column, V3<V>& transmittance, V3<V>& inscatter) {
  const V c = Dot3(dir, Set3(d, p.sun_direction));
  const V one_plus_c2 = hn::Add(hn::Set(d, 1.0f), hn::Mul(c, c));
  const V q = hn::Sub(hn::Set(d, p.atmosphere_mie_a), hn::Mul(hn::Set(d, p.atmosphere_mie_b), c));
  const V mie_phase = hn::Div(one_plus_c2, hn::Mul(q, hn::Sqrt(q)));  // q >= 0.0025
  const Vec3<float>& e = p.atmosphere_extinction_log2;
  const Vec3<float>& a = p.atmosphere_camera_sun_depth_log2;
  const Vec3<float>& r = p.atmosphere_rayleigh_sun;
  const Vec3<float>& m = p.atmosphere_mie_sun;
  ScatterChannel<kTransmittance>(d, e.x, a.x, r.x, m.x, one_plus_c2, mie_phase, column,
                                 end_sun_column, transmittance.x, inscatter.x);
  ScatterChannel<kTransmittance>(d, e.y, a.y, r.y, m.y, one_plus_c2, mie_phase, column,
                                 end_sun_column, transmittance.y, inscatter.y);
  ScatterChannel<kTransmittance>(d, e.z, a.z, r.z, m.z, one_plus_c2, mie_phase, column,
                                 end_sun_column, transmittance.z, inscatter.z);
}

// atmosphere_over (atmosphere.cc).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> AtmosphereOver(D d, const ShadeParams<float>& p, const V3<V>& radiance,
                                const V3<V>& dir, V distance) {
  distance = StdMin(distance, hn::Set(d, float(limits::kMaxCameraRelativeDistance)));
  const V w = hn::Mul(hn::Mul(dir.y, distance), hn::Set(d, p.atmosphere_inv_scale_height));
  const V rise = hn::Abs(w);
  const V fall = Exp2Det(d, hn::Mul(hn::Neg(rise), hn::Set(d, float(kLog2e))));
  const V length = hn::Mul(distance, ColumnGrowth(d, rise, fall));
  const V dense =
      Exp2Det(d, hn::Add(hn::Set(d, p.atmosphere_log2_density),
                         StdMax(hn::Mul(hn::Neg(w), hn::Set(d, float(kLog2e))), hn::Zero(d))));
  const V slope_length = hn::Set(d, p.atmosphere_sun_slope_length);
  const V sun_length =
      hn::IfThenElse(hn::Gt(w, hn::Zero(d)), hn::Mul(slope_length, fall), slope_length);
  const V density =
      StdMin(dense, hn::Div(hn::Set(d, float(kMaxOpticalDepth)), StdMax(length, sun_length)));
  V3<V> transmittance, inscatter;
  Scatter<true>(d, p, dir, hn::Mul(density, length), hn::Mul(density, sun_length), transmittance,
                inscatter);
  return Add3(Mul3(radiance, transmittance), inscatter);
}

// atmosphere_sky (atmosphere.cc).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V3<V> AtmosphereSky(D d, const ShadeParams<float>& p, const V3<V>& dir) {
  const V mu = StdMax(dir.y, hn::Zero(d));
  const V slope = hn::Mul(
      hn::Set(d, 0.5f),
      hn::Add(mu, hn::Sqrt(hn::Add(hn::Mul(mu, mu), hn::Set(d, p.atmosphere_grazing_term)))));
  const V column = StdMin(hn::Mul(hn::Set(d, p.atmosphere_density),
                                  hn::Div(hn::Set(d, p.atmosphere_scale_height), slope)),
                          hn::Set(d, float(kMaxOpticalDepth)));
  V3<V> unused, inscatter;
  Scatter<false>(d, p, dir, column, hn::Zero(d), unused, inscatter);
  return inscatter;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
