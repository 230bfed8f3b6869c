// Per-target water of core/water.cc for float, one pixel per lane: wave_normal (three drifting
// octaves of the lattice's quintic gradient, each faded by the footprint) and shade_water
// (Fresnel-weighted sky reflection over the extinguished ground and the water body), with the
// scalar code's operations in its order. An octave whose fade is 0 in every lane that needs it
// is skipped, as the scalar loop skips it per pixel.
// Included by a kernel's -inl.h inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_WATER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_WATER_INL_H_
#undef RELIEF_SIMD_WATER_INL_H_
#else
#define RELIEF_SIMD_WATER_INL_H_
#endif

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/det_math-inl.h"
#include "simd/lattice-inl.h"
#include "simd/shade_calls-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// fade_slope<kQuintic> (interpolant.h): ((30 t) t (t - 1)) (t - 1).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V QuinticFadeSlope(D d, V t) {
  const V t1 = hn::Sub(t, hn::Set(d, 1.0f));
  return hn::Mul(hn::Mul(hn::Mul(hn::Mul(hn::Set(d, 30.0f), t), t), t1), t1);
}

// sample_lattice_gradient<kQuintic> (interpolant.h), the gradient only: locate_cell, four
// gathers, the lerps and the fade slopes.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void SampleLatticeGradientQuintic(D d, const LatticeView& l, V px, V pz, V& dpx,
                                             V& dpz) {
  const hn::RebindToSigned<D> di;
  const V period = hn::Set(d, l.period);
  const V inv_period = hn::Set(d, l.inv_period);
  const V wx = WrapPeriod(d, px, period, inv_period);
  const V wz = WrapPeriod(d, pz, period, inv_period);
  const V fx = hn::Floor(wx);
  const V fz = hn::Floor(wz);
  const auto mask = hn::Set(di, l.mask);
  const auto one = hn::Set(di, 1);
  const auto i0 = hn::And(hn::ConvertTo(di, fx), mask);
  const auto j0 = hn::And(hn::ConvertTo(di, fz), mask);
  const auto i1 = hn::And(hn::Add(i0, one), mask);
  const auto j1 = hn::And(hn::Add(j0, one), mask);
  const V cx = hn::Sub(wx, fx), cz = hn::Sub(wz, fz);
  const V tx = Fade<Interpolant::kQuintic>(d, cx);
  const V tz = Fade<Interpolant::kQuintic>(d, cz);
  V v00, v10, v01, v11;
  LatticeCorners(d, l, i0, i1, j0, j1, v00, v10, v01, v11);
  const V bottom = hn::Add(v00, hn::Mul(tx, hn::Sub(v10, v00)));
  const V top = hn::Add(v01, hn::Mul(tx, hn::Sub(v11, v01)));
  const V slope_bottom = hn::Sub(v10, v00), slope_top = hn::Sub(v11, v01);
  dpx = hn::Mul(QuinticFadeSlope(d, cx),
                hn::Add(slope_bottom, hn::Mul(tz, hn::Sub(slope_top, slope_bottom))));
  dpz = hn::Mul(QuinticFadeSlope(d, cz), hn::Sub(top, bottom));
}

// wave_normal (water.cc) at camera-relative surface positions (x, z), for the lanes of
// `active` (the others' results are unspecified).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> WaveNormal(D d, const ShadeParams<float>& p, const LatticeView& lattice, V x, V z,
                            V strength, V footprint, M active) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  V gx = zero, gz = zero;
  for (int o = 0; o < kWaveOctaves; ++o) {
    const V inv = hn::Set(d, p.wave_inv_length[o]);
    const V fade = Clamp01(d, hn::Sub(one, hn::Mul(hn::Mul(hn::Set(d, 2.0f), footprint), inv)));
    const M used = hn::AndNot(hn::Eq(fade, zero), active);  // scalar: skipped where fade == 0
    if (hn::AllFalse(d, used)) {
      continue;
    }
    V dx, dz;
    SampleLatticeGradientQuintic(d, lattice,
                                 hn::Add(hn::Set(d, p.wave_offset_x[o]), hn::Mul(x, inv)),
                                 hn::Add(hn::Set(d, p.wave_offset_z[o]), hn::Mul(z, inv)), dx, dz);
    const V a = hn::Mul(hn::Set(d, p.wave_amplitude[o]), fade);
    gx = hn::IfThenElse(used, hn::Add(gx, hn::Mul(a, dx)), gx);
    gz = hn::IfThenElse(used, hn::Add(gz, hn::Mul(a, dz)), gz);
  }
  const V3<V> bumped{hn::Mul(hn::Neg(gx), strength), one, hn::Mul(hn::Neg(gz), strength)};
  return NormalizeOr(d, bumped, V3<V>{zero, one, zero});
}

// shade_water (water.cc) for the lanes of `active` (the others' results are unspecified).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> ShadeWater(D d, const ShadeParams<float>& p, const LatticeView& lattice,
                            const SkyboxView& skybox, const V3<V>& view, V surface_distance,
                            V depth, const V3<V>& ground, V footprint, V sun_share,
                            const V3<V>& terrain, V terrain_weight, M active, ShadeWork& work) {
  constexpr double kFresnelF0 = 0.02;             // water.cc
  constexpr double kRelativeIndex = 1.0 / 1.333;  // water.cc
  constexpr double kMinTransmittedCosine = 0.1;   // water.cc
  const V one = hn::Set(d, 1.0f);
  const V f = Smooth01(d, hn::Mul(depth, hn::Set(d, p.inv_full_depth)));
  const V3<V> s = Scale3(view, surface_distance);
  const V3<V> n = WaveNormal(d, p, lattice, s.x, s.z, hn::Mul(hn::Set(d, p.wave_strength), f),
                             footprint, active);

  const V view_n = Dot3(view, n);
  const V cos_i = Clamp01(d, hn::Neg(view_n));
  const V m = hn::Sub(one, cos_i);
  const V fresnel = hn::Add(hn::Set(d, float(kFresnelF0)),
                            hn::Mul(hn::Set(d, float(1 - kFresnelF0)),
                                    hn::Mul(hn::Mul(hn::Mul(hn::Mul(m, m), m), m), m)));
  V3<V> reflected = Sub3(view, Scale3(n, hn::Mul(hn::Set(d, 2.0f), view_n)));
  reflected.y = hn::Abs(reflected.y);
  V3<V> sky = SkyRadiance(d, p, skybox, reflected, sun_share);
  if (p.clouds) {  // from the surface point, to the sky
    sky = CloudsOverLanes(p, lattice, sky, s, surface_distance, reflected,
                          hn::Set(d, float(limits::kMaxCameraRelativeDistance)), active, work);
  }
  if (p.terrain_reflections) {  // the terrain the reflected ray meets (water.cc)
    sky = Add3(sky, Scale3(Sub3(terrain, sky), terrain_weight));
  }

  const float eta = float(kRelativeIndex);
  const V eta_v = hn::Set(d, eta);
  const V k = hn::Sub(one, hn::Mul(hn::Set(d, eta * eta), hn::Sub(one, hn::Mul(cos_i, cos_i))));
  const V3<V> t = Add3(Scale3(view, eta_v), Scale3(n, hn::Sub(hn::Mul(eta_v, cos_i), hn::Sqrt(k))));
  const V path = hn::Div(depth, StdMax(hn::Abs(t.y), hn::Set(d, float(kMinTransmittedCosine))));
  const Vec3<float>& e = p.extinction_log2;
  const V3<V> transmitted{Exp2Det(d, hn::Mul(hn::Set(d, -e.x), path)),
                          Exp2Det(d, hn::Mul(hn::Set(d, -e.y), path)),
                          Exp2Det(d, hn::Mul(hn::Set(d, -e.z), path))};

  // Per frame, in float as the scalar code forms it per pixel; then past the terrain's cast
  // shadow and through the cloud layer above the surface point.
  const Vec3<float> sun_part =
      p.sun * (0.5f * (0.0f < p.sun_direction.y ? p.sun_direction.y : 0.0f));
  V3<V> sun_lit = Scale3(Set3(d, sun_part), sun_share);
  if (p.clouds) {
    sun_lit = Scale3(sun_lit, CloudSunShareLanes(p, lattice, s, footprint, active, work));
  }
  const V3<V> body_light = Add3(Set3(d, p.sky_light), sun_lit);
  const V3<V> body = Mul3(Mix3(Set3(d, p.shallow), Set3(d, p.deep), f), body_light);
  const V3<V> under =
      Add3(Mul3(ground, transmitted), Mul3(body, Sub3(Set3(d, 1.0f, 1.0f, 1.0f), transmitted)));
  const V reflectivity = hn::Add(hn::Set(d, float(0.3)), hn::Mul(hn::Set(d, float(0.7)), f));
  return Mix3(under, sky, hn::Mul(fresnel, reflectivity));
}

// surface_footprint (shade.cc): distance pixel_angle / max(|view.y|, 0.05).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SurfaceFootprint(D d, const ShadeParams<float>& p, V distance, V view_y) {
  return hn::Div(hn::Mul(distance, hn::Set(d, p.pixel_angle)),
                 StdMax(hn::Abs(view_y), hn::Set(d, float(0.05))));
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
