#include "core/sky.h"

#include <cmath>

#include "core/atmosphere.h"
#include "core/det_math.h"
#include "core/limits.h"

namespace relief {

namespace {

// ((1 + c) / 2)^(2^n) by repeated squaring: no pow.
template <class Real>
Real power_of_half_cosine(Real c, int squarings) {
  Real x = clamp01((Real(1) + c) * Real(0.5));
  for (int k = 0; k < squarings; ++k) {
    x = x * x;
  }
  return x;
}

// The sun disc (20 x the sun) with its smooth edge and the halo around it, in direction d; the
// disc times `disc_share`, the share of it that the terrain leaves in view (sky.h).
// Under the atmosphere no halo: its haze scatters the glow (atmosphere.h), and p.sun is
// already the light that reaches the camera's height.
template <class Real>
Vec3<Real> sun_light(const ShadeParams<Real>& p, const Vec3<Real>& d, Real disc_share) {
  const Vec3<Real>& sun = p.sun;
  const Real c = dot(d, p.sun_direction);
  const Real inner = p.sun_cos_inner, outer = p.sun_cos_outer;
  const Real disc = inner > outer ? smooth01((c - outer) / (inner - outer)) : Real(c >= inner);
  if (p.atmosphere != 0) {
    return sun * (Real(20) * disc * disc_share);
  }
  const Real halo = Real(0.06) * power_of_half_cosine(c, 5);
  return sun * (Real(20) * disc * disc_share + halo);
}

}  // namespace

template <class Real>
Vec3<Real> sky_radiance(const ShadeParams<Real>& p, const Skybox* skybox, const Vec3<Real>& d,
                        Real disc_share) {
  if (p.skybox != 0 && skybox != nullptr) {
    const Vec3<Real> color = skybox_radiance(*skybox, d);
    return p.skybox_sun != 0 ? color + sun_light(p, d, disc_share) : color;
  }
  if (p.atmosphere != 0) {
    return atmosphere_sky(p, d) + sun_light(p, d, disc_share);
  }
  const Vec3<Real>& zenith = p.zenith;
  const Vec3<Real>& horizon = p.horizon;
  Vec3<Real> color = horizon;
  if (d.y > Real(0)) {
    color = mix(horizon, zenith, std::sqrt(d.y));  // domain: d.y > 0
  }
  return color + sun_light(p, d, disc_share);
}

template <class Real>
Vec3<Real> fog_color(const ShadeParams<Real>& p, const Vec3<Real>& d) {
  if (p.atmosphere != 0) {
    // The air along the whole ray (kMaxCameraRelativeDistance: below the horizon the limit at
    // infinity), as the fog's colour is its own limit there.
    return atmosphere_over(p, Vec3<Real>{0, 0, 0}, d, Real(limits::kMaxCameraRelativeDistance));
  }
  const Real c = dot(d, p.sun_direction);
  return p.horizon + p.sun * (Real(0.05) * power_of_half_cosine(c, 3));
}

template <class Real>
Vec3<Real> apply_fog(const ShadeParams<Real>& p, const Vec3<Real>& radiance, const Vec3<Real>& d,
                     Real distance) {
  if (p.atmosphere != 0) {
    return atmosphere_over(p, radiance, d, distance);
  }
  const Real clear = exp2_det(-p.fog_density_log2 * distance);  // in (0, 1]
  if (!(clear < Real(1))) {
    return radiance;  // no fog: exactly the radiance (a mix with weight 1 could round)
  }
  return mix(fog_color(p, d), radiance, clear);
}

template Vec3<float> sky_radiance<float>(const ShadeParams<float>&, const Skybox*,
                                         const Vec3<float>&, float);
template Vec3<double> sky_radiance<double>(const ShadeParams<double>&, const Skybox*,
                                           const Vec3<double>&, double);
template Vec3<float> fog_color<float>(const ShadeParams<float>&, const Vec3<float>&);
template Vec3<double> fog_color<double>(const ShadeParams<double>&, const Vec3<double>&);
template Vec3<float> apply_fog<float>(const ShadeParams<float>&, const Vec3<float>&,
                                      const Vec3<float>&, float);
template Vec3<double> apply_fog<double>(const ShadeParams<double>&, const Vec3<double>&,
                                        const Vec3<double>&, double);

}  // namespace relief
