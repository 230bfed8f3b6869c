// Per-target cloud layer of core/clouds.cc for float, one pixel per lane: cloud_path,
// cloud_density (the warp, the octaves faded by the footprint, the density's threshold),
// cloud_sun_share and clouds_over, with the scalar code's operations in its order. The frame
// reads one point per path (cloud_steps = 1; the ground truth's several points run in the
// double reference only). An octave whose fade is 0 in every lane that needs it is skipped, as
// the scalar loop stops there per pixel (the fades fall with each octave: a cell is exactly
// half the last). Lanes outside a mask read the lattice at 0 and are discarded.
// Compiled in its own translation unit, simd/clouds.cc, whose out-of-line entries the shading
// calls (simd/shade_calls-inl.h): inlined in four places of simd/shade.cc (terrain, background,
// the water's reflection and body) they nearly doubled its Release compile and more than doubled
// its compile under ASan + UBSan, already the slowest of the build (over 13 minutes before the
// layer on the 2-core machine).
// Included by simd/clouds.cc inside its per-target section (Highway's re-inclusion guard).
#if defined(RELIEF_SIMD_CLOUDS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_CLOUDS_INL_H_
#undef RELIEF_SIMD_CLOUDS_INL_H_
#else
#define RELIEF_SIMD_CLOUDS_INL_H_
#endif

#include <algorithm>
#include <cmath>

#include <hwy/highway.h>

#include "core/cloud_plan.h"
#include "core/clouds.h"
#include "core/limits.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/det_math-inl.h"
#include "simd/lattice-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// cloud_path (clouds.cc): the path's start and its length inside the layer.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void CloudPathLanes(D d, const ShadeParams<float>& p, V y0, V dy, V end, V& start,
                               V& length) {
  const V zero = hn::Zero(d);
  const V slope = hn::Set(d, float(kCloudMinSlope));
  const V safe_dy = hn::IfThenElse(hn::Ge(dy, zero), StdMax(dy, slope), StdMin(dy, hn::Neg(slope)));
  const V t_bottom = hn::Div(hn::Sub(hn::Set(d, p.cloud_bottom), y0), safe_dy);
  const V t_top = hn::Div(hn::Sub(hn::Set(d, p.cloud_top), y0), safe_dy);
  start = StdMax(zero, StdMin(t_bottom, t_top));
  const V stop = StdMin(end, StdMax(t_bottom, t_top));
  length = StdMax(zero, hn::Sub(stop, start));
}

// octave_fade (clouds.cc): min(1, max(0, 2 - (2 footprint) inv_cell)).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V OctaveFade(D d, V footprint, float inv_cell) {
  const V two = hn::Set(d, 2.0f);
  return StdMin(
      hn::Set(d, 1.0f),
      StdMax(hn::Zero(d), hn::Sub(two, hn::Mul(hn::Mul(two, footprint), hn::Set(d, inv_cell)))));
}

// cloud_density (clouds.cc) for the lanes of `active`; the others hold the mean density.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V CloudDensity(D d, const ShadeParams<float>& p, const LatticeView& lattice, V x, V z,
                          V footprint, M active, ShadeWork& work) {
  const V zero = hn::Zero(d);
  const V mean = hn::Set(d, p.cloud_mean_density);
  const V fade0 = OctaveFade(d, footprint, p.cloud_inv_scale[0]);
  const M sampled = hn::And(active, hn::Gt(fade0, zero));
  const std::size_t count = hn::CountTrue(d, sampled);
  if (count == 0) {
    return mean;
  }
  x = hn::IfThenElseZero(sampled, x);
  z = hn::IfThenElseZero(sampled, z);
  const V period = hn::Set(d, lattice.period), inv_period = hn::Set(d, lattice.inv_period);
  V warp_x = zero, warp_z = zero;
  if (p.cloud_warped) {
    const V inv = hn::Set(d, p.cloud_inv_scale[0]);
    const V ux = hn::Mul(x, inv), vz = hn::Mul(z, inv);
    warp_x = SampleLattice<Interpolant::kCubic>(d, lattice, period, inv_period,
                                                hn::Add(hn::Set(d, p.cloud_warp_offset[0]), ux),
                                                hn::Add(hn::Set(d, p.cloud_warp_offset[1]), vz));
    warp_z = SampleLattice<Interpolant::kCubic>(d, lattice, period, inv_period,
                                                hn::Add(hn::Set(d, p.cloud_warp_offset[2]), ux),
                                                hn::Add(hn::Set(d, p.cloud_warp_offset[3]), vz));
    work.cloud_lookups += 2 * count;
  }
  V n = zero;
  for (int i = 0; i < p.cloud_octaves; ++i) {
    const V fade = OctaveFade(d, footprint, p.cloud_inv_scale[i]);
    const M octave = hn::And(sampled, hn::Gt(fade, zero));
    const std::size_t lanes = hn::CountTrue(d, octave);
    if (lanes == 0) {
      break;
    }
    const V inv = hn::Set(d, p.cloud_inv_scale[i]);
    const V gain = hn::Set(d, p.cloud_warp_gain[i]);
    const V u =
        hn::Add(hn::Add(hn::Set(d, p.cloud_offset_x[i]), hn::Mul(x, inv)), hn::Mul(warp_x, gain));
    const V v =
        hn::Add(hn::Add(hn::Set(d, p.cloud_offset_z[i]), hn::Mul(z, inv)), hn::Mul(warp_z, gain));
    const V s = SampleLattice<Interpolant::kCubic>(d, lattice, period, inv_period, u, v);
    n = hn::IfThenElse(octave,
                       hn::Add(n, hn::Mul(hn::Mul(hn::Set(d, p.cloud_amplitude[i]), fade), s)), n);
    work.cloud_lookups += lanes;
  }
  const V density =
      StdMin(hn::Set(d, 1.0f), StdMax(zero, hn::Mul(hn::Sub(n, hn::Set(d, p.cloud_threshold)),
                                                    hn::Set(d, p.cloud_sharpness))));
  return hn::IfThenElse(sampled, hn::Add(mean, hn::Mul(hn::Sub(density, mean), fade0)), mean);
}

// path_density (clouds.cc) at one point, the path's middle, its footprint widened to the
// path's horizontal span (`horizontal`: the length of dir's (x, z)): 0 + D, times 1 / 1.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V CloudMiddleDensity(D d, const ShadeParams<float>& p, const LatticeView& lattice,
                                const V3<V>& origin, const V3<V>& dir, V horizontal, V start,
                                V length, V footprint, M active, ShadeWork& work) {
  const V one = hn::Set(d, 1.0f);
  const V span =
      hn::Mul(hn::Mul(hn::Mul(length, horizontal), one), hn::Set(d, float(kCloudSpanFootprint)));
  const V t = hn::Add(start, hn::Mul(length, hn::Set(d, 0.5f)));
  const V x = hn::Add(origin.x, hn::Mul(t, dir.x));
  const V z = hn::Add(origin.z, hn::Mul(t, dir.z));
  return hn::Add(hn::Zero(d),
                 CloudDensity(d, p, lattice, x, z, StdMax(footprint, span), active, work));
}

// cloud_sun_share (clouds.cc) of the points `position` of the lanes of `active`; 1 elsewhere.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V CloudSunShare(D d, const ShadeParams<float>& p, const LatticeView& lattice,
                           const V3<V>& position, V footprint, M active, ShadeWork& work) {
  const V one = hn::Set(d, 1.0f);
  const Vec3<float>& s = p.sun_direction;
  if (!(s.y > 0.0f)) {
    return one;
  }
  const V3<V> sun = Set3(d, s);
  V start, length;
  CloudPathLanes(d, p, position.y, hn::Set(d, std::max(s.y, float(kCloudMinSunSine))),
                 hn::Set(d, float(limits::kMaxCameraRelativeDistance)), start, length);
  const M crossing = hn::And(active, hn::Gt(length, hn::Zero(d)));
  const std::size_t count = hn::CountTrue(d, crossing);
  if (count == 0) {
    return one;
  }
  work.cloud_sun_paths += count;
  const V horizontal = hn::Set(d, std::sqrt(s.x * s.x + s.z * s.z));
  const V density = CloudMiddleDensity(d, p, lattice, position, sun, horizontal, start, length,
                                       footprint, crossing, work);
  const V depth = hn::Mul(hn::Mul(hn::Set(d, p.cloud_extinction_log2), density), length);
  return hn::IfThenElse(crossing, Exp2Det(d, hn::Neg(depth)), one);
}

// clouds_over_from (clouds.cc) for the lanes of `active`: `radiance` seen along unit `dir` from
// the camera-relative `origin` (`origin_distance` from the camera) up to `end` through the
// layer; the radiance itself elsewhere.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> CloudsOverFrom(D d, const ShadeParams<float>& p, const LatticeView& lattice,
                                const V3<V>& radiance, const V3<V>& origin, V origin_distance,
                                const V3<V>& dir, V end, M active, ShadeWork& work) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  V start, length;
  CloudPathLanes(d, p, origin.y, dir.y, end, start, length);
  const M crossing = hn::And(active, hn::Gt(length, zero));
  const std::size_t count = hn::CountTrue(d, crossing);
  if (count == 0) {
    return radiance;
  }
  work.cloud_view_paths += count;
  const V stretch =
      hn::Div(hn::Set(d, p.pixel_angle), StdMax(hn::Abs(dir.y), hn::Set(d, float(0.05))));
  const V t = hn::Add(start, hn::Mul(length, hn::Set(d, 0.5f)));
  const V density = CloudMiddleDensity(
      d, p, lattice, origin, dir, hn::Sqrt(hn::Add(hn::Mul(dir.x, dir.x), hn::Mul(dir.z, dir.z))),
      start, length, hn::Mul(hn::Add(origin_distance, t), stretch), crossing, work);
  const V transmittance =
      Exp2Det(d, hn::Neg(hn::Mul(hn::Mul(hn::Set(d, p.cloud_extinction_log2), density), length)));
  const V3<V> light =
      Add3(Set3(d, p.cloud_sky_light),
           Scale3(Set3(d, p.cloud_sun_light),
                  Exp2Det(d, hn::Neg(hn::Mul(density, hn::Set(d, p.cloud_sun_depth_log2))))));
  const V middle = hn::Add(origin_distance, t);
  const V3<V> seen = p.fog_enabled ? ApplyFog(d, p, light, dir, middle) : light;
  const V3<V> over =
      Add3(Scale3(radiance, transmittance), Scale3(seen, hn::Sub(one, transmittance)));
  return Select3(crossing, over, radiance);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
