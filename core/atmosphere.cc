#include "core/atmosphere.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/limits.h"

namespace relief {

namespace {

// The air's light along a ray whose column is `column` and where the sun's column above the
// ray's end is `end_sun_column` (both at most kMaxOpticalDepth): per channel the in-scattered
// light (core/atmosphere.h, the closed form of I), and where `transmittance` is given the
// transmittance.
template <class Real>
void scatter(const ShadeParams<Real>& p, const Vec3<Real>& d, Real column, Real end_sun_column,
             Vec3<Real>* transmittance, Vec3<Real>& inscatter) {
  const Real c = dot(d, p.sun_direction);
  const Real one_plus_c2 = Real(1) + c * c;
  const Real q = p.atmosphere_mie_a - p.atmosphere_mie_b * c;  // >= (1 - g)^2 = 0.0025
  const Real mie_phase = one_plus_c2 / (q * std::sqrt(q));
  const Real extinction[3] = {p.atmosphere_extinction_log2.x, p.atmosphere_extinction_log2.y,
                              p.atmosphere_extinction_log2.z};
  const Real camera_sun[3] = {p.atmosphere_camera_sun_depth_log2.x,
                              p.atmosphere_camera_sun_depth_log2.y,
                              p.atmosphere_camera_sun_depth_log2.z};
  const Real rayleigh[3] = {p.atmosphere_rayleigh_sun.x, p.atmosphere_rayleigh_sun.y,
                            p.atmosphere_rayleigh_sun.z};
  const Real mie[3] = {p.atmosphere_mie_sun.x, p.atmosphere_mie_sun.y, p.atmosphere_mie_sun.z};
  Real t[3], s[3];
  for (int k = 0; k < 3; ++k) {
    const Real view = extinction[k] * column;  // beta_e tau(T) / ln 2
    if (transmittance != nullptr) {
      t[k] = exp2_det(-view);
    }
    const Real a = camera_sun[k];                          // A / ln 2
    const Real b = view + extinction[k] * end_sun_column;  // B / ln 2
    const Real z = std::abs(a - b);
    const Real integral =
        exp2_det(-std::min(a, b)) * (column * column_growth(z * Real(kLn2), exp2_det(-z)));
    s[k] = (rayleigh[k] * one_plus_c2 + mie[k] * mie_phase) * integral;
  }
  if (transmittance != nullptr) {
    *transmittance = {t[0], t[1], t[2]};
  }
  inscatter = {s[0], s[1], s[2]};
}

}  // namespace

template <class Real>
Real column_growth(Real z, Real e) {
  if (std::abs(z) < Real(kGrowthSeriesLimit)) {
    Real series = Real(kGrowthSeries[kGrowthTerms - 1]);
    for (int k = kGrowthTerms - 2; k >= 0; --k) {
      series = Real(kGrowthSeries[k]) + z * series;
    }
    return series;
  }
  return (Real(1) - e) / z;  // z != 0 here
}

template <class Real>
Vec3<Real> atmosphere_over(const ShadeParams<Real>& p, const Vec3<Real>& radiance,
                           const Vec3<Real>& d, Real distance) {
  distance = std::min(distance, Real(limits::kMaxCameraRelativeDistance));
  const Real w = d.y * distance * p.atmosphere_inv_scale_height;  // ln(rho0 / rho(T))
  const Real rise = std::abs(w);
  const Real fall = exp2_det(-rise * Real(kLog2e));  // the thinner end's density / the denser's
  const Real length = distance * column_growth(rise, fall);  // T phi(|w|) <= min(T, H / |mu|)
  // The denser end: the camera where the ray climbs (w > 0), else the ray's end.
  const Real dense = exp2_det(p.atmosphere_log2_density + std::max(-w * Real(kLog2e), Real(0)));
  const Real sun_length =
      w > Real(0) ? p.atmosphere_sun_slope_length * fall : p.atmosphere_sun_slope_length;
  // Domain: sun_length >= H / mu_s 2^-125 > 0. Both columns capped by one factor.
  const Real density = std::min(dense, Real(kMaxOpticalDepth) / std::max(length, sun_length));
  Vec3<Real> transmittance, inscatter;
  scatter(p, d, density * length, density * sun_length, &transmittance, inscatter);
  return radiance * transmittance + inscatter;
}

template <class Real>
Vec3<Real> atmosphere_sky(const ShadeParams<Real>& p, const Vec3<Real>& d) {
  const Real mu = std::max(d.y, Real(0));
  // sqrt's domain: mu^2 + 4 c^2 > 0; slope >= c > 0 (atmosphere_plan.h).
  const Real slope = Real(0.5) * (mu + std::sqrt(mu * mu + p.atmosphere_grazing_term));
  const Real column =
      std::min(p.atmosphere_density * (p.atmosphere_scale_height / slope), Real(kMaxOpticalDepth));
  Vec3<Real> inscatter;
  scatter(p, d, column, Real(0), static_cast<Vec3<Real>*>(nullptr), inscatter);
  return inscatter;
}

template float column_growth<float>(float, float);
template double column_growth<double>(double, double);
template Vec3<float> atmosphere_over<float>(const ShadeParams<float>&, const Vec3<float>&,
                                            const Vec3<float>&, float);
template Vec3<double> atmosphere_over<double>(const ShadeParams<double>&, const Vec3<double>&,
                                              const Vec3<double>&, double);
template Vec3<float> atmosphere_sky<float>(const ShadeParams<float>&, const Vec3<float>&);
template Vec3<double> atmosphere_sky<double>(const ShadeParams<double>&, const Vec3<double>&);

}  // namespace relief
