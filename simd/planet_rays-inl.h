// Per-target view rays of a planet frame's background (core/planet_shading.h,
// planet_background_ray): what each lane's ray meets, in double lanes with the scalar code's
// operations in its order (atan2_det and sin_cos_det of core/det_math.h included), handed to
// the float lanes that shade it.
// Included by simd/planet_shade-inl.h inside its per-target section (Highway's re-inclusion
// guard).
#if defined(RELIEF_SIMD_PLANET_RAYS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PLANET_RAYS_INL_H_
#undef RELIEF_SIMD_PLANET_RAYS_INL_H_
#else
#define RELIEF_SIMD_PLANET_RAYS_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/det_math.h"
#include "core/planet_shading.h"
#include "core/stage_params.h"
#include "simd/det_trig-inl.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// planet_background_ray of each lane's view ray, one float lane per pixel.
template <class D>
struct PlanetRayVectors {
  hn::Mask<D> water, ground;  // the kinds (sky where neither)
  V3<hn::Vec<D>> up;          // water lanes: the sphere's normal at the hit
  hn::Vec<D> surface;         // water lanes: the distance to the hit
  V3<hn::Vec<D>> sky;         // sky lanes: the direction the sky gradient reads
};

// planet_sphere_hit (core/planet_shading.h) per lane: the near side's distance, < 0 for a miss.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE VD SphereHitDouble(DD dd, VD unit_y, double center_distance, double c) {
  const VD zero = hn::Zero(dd);
  if (!(c > 0.0)) {
    return hn::Set(dd, -1.0);
  }
  const VD b = hn::Mul(unit_y, hn::Set(dd, center_distance));
  const VD c_v = hn::Set(dd, c);
  const VD disc = hn::Sub(hn::Mul(b, b), c_v);
  const auto hit = hn::And(hn::Lt(b, zero), hn::Ge(disc, zero));
  // Domain: -b > 0 and disc >= 0 in the lanes that hit; the others divide by 1.
  const VD denominator = hn::IfThenElse(
      hit, hn::Add(hn::Neg(b), hn::Sqrt(hn::IfThenElseZero(hit, disc))), hn::Set(dd, 1.0));
  return hn::IfThenElse(hit, hn::Div(c_v, denominator), hn::Set(dd, -1.0));
}

// The rays of pixels (px0 + lane, py), formed in double as background_radiance forms them
// (shade.cc), met with the spheres as planet_background_ray meets them, in double lanes (the
// sky's direction through Atan2Double and SinCosDouble), each result rounded once to float.
template <class D>
HWY_INLINE PlanetRayVectors<D> PlanetRays(D d, const ShadeParams<float>& p, int px0, int py) {
  constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  const hn::ScalableTag<double> dd;
  const hn::Rebind<float, decltype(dd)> df;
  using VD = hn::Vec<decltype(dd)>;
  HWY_ALIGN float kind[kMaxLanes], up[3][kMaxLanes], sky[3][kMaxLanes], surface[kMaxLanes];
  const std::size_t lanes = hn::Lanes(d), wide = hn::Lanes(dd);
  const double ndc_y = 2.0 * (py + 0.5) / p.height - 1.0;
  const VD sy = hn::Set(dd, ndc_y * p.tan_half_fov_y);
  const VD zero = hn::Zero(dd), one = hn::Set(dd, 1.0);
  const double center = p.planet_center_distance;
  for (std::size_t first = 0; first < lanes; first += wide) {
    const VD px = hn::Iota(dd, double(px0) + double(first));
    const VD ndc_x = hn::Sub(hn::Div(hn::Mul(hn::Set(dd, 2.0), hn::Add(px, hn::Set(dd, 0.5))),
                                     hn::Set(dd, double(p.width))),
                             one);
    const VD sx = hn::Mul(ndc_x, hn::Set(dd, p.tan_half_fov_x));
    VD ray[3];
    for (int c = 0; c < 3; ++c) {
      ray[c] = hn::Add(hn::Add(hn::Set(dd, p.forward[c]), hn::Mul(sx, hn::Set(dd, p.right[c]))),
                       hn::Mul(sy, hn::Set(dd, p.up[c])));
    }
    const VD length = hn::Sqrt(hn::Add(hn::Add(hn::Mul(ray[0], ray[0]), hn::Mul(ray[1], ray[1])),
                                       hn::Mul(ray[2], ray[2])));
    const VD unit[3] = {hn::Div(ray[0], length), hn::Div(ray[1], length),
                        hn::Div(ray[2], length)};  // length >= 1
    // Water: the sphere's hit, its normal there (the hit's length is the radius, > 0).
    auto water = hn::Lt(zero, zero);  // none
    VD up_v[3] = {zero, one, zero}, surface_v = zero;
    if (p.water_enabled != 0) {
      const VD t = SphereHitDouble(dd, unit[1], center, p.planet_water_c);
      water = hn::Ge(t, zero);
      const VD hit[3] = {hn::Mul(t, unit[0]), hn::Add(hn::Mul(t, unit[1]), hn::Set(dd, center)),
                         hn::Mul(t, unit[2])};
      const VD radius = hn::Sqrt(hn::Add(hn::Add(hn::Mul(hit[0], hit[0]), hn::Mul(hit[1], hit[1])),
                                         hn::Mul(hit[2], hit[2])));
      const VD safe_radius = hn::IfThenElse(water, radius, one);
      for (int c = 0; c < 3; ++c) {
        up_v[c] = hn::IfThenElse(water, hn::Div(hit[c], safe_radius), up_v[c]);
      }
      surface_v = hn::IfThenElseZero(water, t);
    }
    const auto ground = p.planet_datum_c > 0.0
                            ? hn::Ge(SphereHitDouble(dd, unit[1], center, p.planet_datum_c), zero)
                            : hn::Lt(unit[1], zero);
    // The sky: planet_sky_direction's elevation from the limb, in the ray's azimuth.
    const VD horizontal = hn::Sqrt(hn::Add(hn::Mul(unit[0], unit[0]), hn::Mul(unit[2], unit[2])));
    const VD alpha = Atan2Lanes(dd, horizontal, hn::Neg(unit[1]));
    const VD limb = hn::Set(dd, p.planet_limb_angle);
    const VD span = hn::Set(dd, 3.14159265358979323846 - p.planet_limb_angle);  // > 0
    const VD t = hn::IfThenElseZero(hn::Gt(alpha, limb), hn::Div(hn::Sub(alpha, limb), span));
    VD sine, cosine;
    SinCosLanes(dd, hn::Mul(t, hn::Set(dd, 1.5707963267948966)), sine, cosine);
    const auto level = hn::Gt(horizontal, zero);  // the divisions' domain
    const VD safe_horizontal = hn::IfThenElse(level, horizontal, one);
    const VD hx = hn::IfThenElseZero(level, hn::Div(unit[0], safe_horizontal));
    const VD hz = hn::IfThenElse(level, hn::Div(unit[2], safe_horizontal), hn::Set(dd, -1.0));
    const VD kind_v = hn::IfThenElse(water, one, hn::IfThenElseZero(ground, hn::Set(dd, 2.0)));
    hn::StoreU(hn::DemoteTo(df, kind_v), df, kind + first);
    for (int c = 0; c < 3; ++c) {
      hn::StoreU(hn::DemoteTo(df, up_v[c]), df, up[c] + first);
    }
    hn::StoreU(hn::DemoteTo(df, surface_v), df, surface + first);
    hn::StoreU(hn::DemoteTo(df, hn::Mul(hx, cosine)), df, sky[0] + first);
    hn::StoreU(hn::DemoteTo(df, sine), df, sky[1] + first);
    hn::StoreU(hn::DemoteTo(df, hn::Mul(hz, cosine)), df, sky[2] + first);
  }
  const auto kinds = hn::Load(d, kind);
  return {hn::Eq(kinds, hn::Set(d, 1.0f)),
          hn::Eq(kinds, hn::Set(d, 2.0f)),
          {hn::Load(d, up[0]), hn::Load(d, up[1]), hn::Load(d, up[2])},
          hn::Load(d, surface),
          {hn::Load(d, sky[0]), hn::Load(d, sky[1]), hn::Load(d, sky[2])}};
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
