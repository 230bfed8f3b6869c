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

// atan_reduced<double> (core/det_math.h): the odd series, Horner in u^2, its coefficients
// +-1 / (2k + 1) rounded as the scalar code's Real(+-1) / Real(2k + 1) rounds them.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE VD AtanReducedDouble(DD dd, VD u) {
  constexpr int n = det_math_detail::TrigTerms<double>::kAtan;
  const VD u2 = hn::Mul(u, u);
  VD series = hn::Set(dd, ((n - 1) % 2 == 0 ? 1.0 : -1.0) / double(2 * (n - 1) + 1));
  for (int k = n - 2; k >= 0; --k) {
    series =
        hn::Add(hn::Mul(series, u2), hn::Set(dd, (k % 2 == 0 ? 1.0 : -1.0) / double(2 * k + 1)));
  }
  return hn::Mul(u, series);
}

// atan2_det<double>(y, x) (core/det_math.h) per lane, its branches as masks; y >= 0.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE VD Atan2Double(DD dd, VD y, VD x) {
  using namespace det_math_detail;
  const VD zero = hn::Zero(dd), one = hn::Set(dd, 1.0);
  const VD ax = hn::IfThenElse(hn::Lt(x, zero), hn::Neg(x), x);  // -0 stays -0, as there
  const auto ax_below = hn::Lt(ax, y);
  const VD lo = hn::IfThenElse(ax_below, ax, y);
  const VD hi = hn::IfThenElse(ax_below, y, ax);
  const auto defined = hn::Gt(hi, zero);  // (0, 0) and NaN: 0
  const VD t = hn::Div(lo, hn::IfThenElse(defined, hi, one));
  const auto big = hn::Gt(t, hn::Set(dd, kTanEighthPi));
  const VD u = hn::IfThenElse(big, hn::Div(hn::Sub(t, one), hn::Add(t, one)), t);
  const VD series = AtanReducedDouble(dd, u);
  VD a = hn::IfThenElse(big, hn::Add(hn::Set(dd, kQuarterPi), series), series);
  a = hn::IfThenElse(hn::Gt(y, ax), hn::Sub(hn::Set(dd, kHalfPi), a), a);
  a = hn::IfThenElse(hn::Lt(x, zero), hn::Sub(hn::Set(dd, 2.0 * kHalfPi), a), a);
  return hn::IfThenElseZero(defined, a);
}

// sin_cos_det<double> (core/det_math.h) per lane for finite x: the quadrant k = round(x / (pi/2))
// clamped to +-64 (as the scalar code's int), kept as an exact double; the reduction in three
// pieces; the series; k mod 4 picks and negates. The sky's direction calls it on [0, pi/2]
// (k 0 or 1: what the frame tests reach); the other quadrants follow the same definition.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE void SinCosDouble(DD dd, VD x, VD& sine, VD& cosine) {
  using namespace det_math_detail;
  using Pieces = HalfPiPieces<double>;
  const VD zero = hn::Zero(dd), half = hn::Set(dd, 0.5);
  VD q = hn::Mul(x, hn::Set(dd, 1.0 / kHalfPi));
  const VD limit = hn::Set(dd, 64.0), neg_limit = hn::Set(dd, -64.0);
  q = hn::IfThenElse(hn::Lt(q, neg_limit), neg_limit, hn::IfThenElse(hn::Gt(q, limit), limit, q));
  // int(q -+ 0.5) truncates toward zero: Trunc gives the same integer, exact in double.
  const VD k = hn::Trunc(hn::IfThenElse(hn::Lt(q, zero), hn::Sub(q, half), hn::Add(q, half)));
  const VD r = hn::Sub(hn::Sub(hn::Sub(x, hn::Mul(k, hn::Set(dd, Pieces::hi))),
                               hn::Mul(k, hn::Set(dd, Pieces::mid))),
                       hn::Mul(k, hn::Set(dd, Pieces::lo)));
  const VD r2 = hn::Mul(r, r);
  constexpr int kSin = TrigTerms<double>::kSin, kCos = TrigTerms<double>::kCos;
  VD ps = hn::Set(dd, kSinCoeffs[kSin - 1]);
  for (int i = kSin - 2; i >= 0; --i) {
    ps = hn::Add(hn::Mul(ps, r2), hn::Set(dd, kSinCoeffs[i]));
  }
  VD pc = hn::Set(dd, kCosCoeffs[kCos - 1]);
  for (int i = kCos - 2; i >= 0; --i) {
    pc = hn::Add(hn::Mul(pc, r2), hn::Set(dd, kCosCoeffs[i]));
  }
  const VD s = hn::Mul(r, ps), c = pc;
  // k & 3 of the integer k (two's complement): k - 4 floor(k / 4), exact for |k| <= 64.
  const VD quadrant =
      hn::Sub(k, hn::Mul(hn::Set(dd, 4.0), hn::Floor(hn::Mul(k, hn::Set(dd, 0.25)))));
  const auto q1 = hn::Eq(quadrant, hn::Set(dd, 1.0));
  const auto q2 = hn::Eq(quadrant, hn::Set(dd, 2.0));
  const auto q3 = hn::Eq(quadrant, hn::Set(dd, 3.0));
  sine = hn::IfThenElse(q1, c, hn::IfThenElse(q2, hn::Neg(s), hn::IfThenElse(q3, hn::Neg(c), s)));
  cosine = hn::IfThenElse(q1, hn::Neg(s), hn::IfThenElse(q2, hn::Neg(c), hn::IfThenElse(q3, s, c)));
}

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
    const VD alpha = Atan2Double(dd, horizontal, hn::Neg(unit[1]));
    const VD limb = hn::Set(dd, p.planet_limb_angle);
    const VD span = hn::Set(dd, 3.14159265358979323846 - p.planet_limb_angle);  // > 0
    const VD t = hn::IfThenElseZero(hn::Gt(alpha, limb), hn::Div(hn::Sub(alpha, limb), span));
    VD sine, cosine;
    SinCosDouble(dd, hn::Mul(t, hn::Set(dd, 1.5707963267948966)), sine, cosine);
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
