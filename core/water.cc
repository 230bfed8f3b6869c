#include "core/water.h"

#include <cmath>

#include "core/clouds.h"
#include "core/det_math.h"
#include "core/interpolant.h"
#include "core/limits.h"
#include "core/sky.h"

namespace relief {

namespace {

constexpr double kFresnelF0 = 0.02;             // air to water at normal incidence
constexpr double kRelativeIndex = 1.0 / 1.333;  // air to water
constexpr double kMinTransmittedCosine = 0.1;   // path length domain guard: |t_y| >= 0.1

}  // namespace

template <class Real>
Vec3<Real> wave_normal(const ShadeParams<Real>& p, const NoiseLattice& lattice, Real x, Real z,
                       Real strength, Real footprint) {
  Real gx = Real(0), gz = Real(0);
  for (int o = 0; o < kWaveOctaves; ++o) {
    const Real inv = p.wave_inv_length[o];
    const Real fade = clamp01(Real(1) - Real(2) * footprint * inv);
    if (fade == Real(0)) {
      continue;
    }
    Real dx = 0, dz = 0;
    sample_lattice_gradient<Interpolant::kQuintic>(lattice, p.wave_offset_x[o] + x * inv,
                                                   p.wave_offset_z[o] + z * inv, dx, dz);
    const Real a = p.wave_amplitude[o] * fade;
    gx = gx + a * dx;
    gz = gz + a * dz;
  }
  return normalize_or(Vec3<Real>{-gx * strength, Real(1), -gz * strength},
                      Vec3<Real>{Real(0), Real(1), Real(0)});
}

template <class Real>
Vec3<Real> shade_water(const ShadeParams<Real>& p, const NoiseLattice& lattice,
                       const Skybox* skybox, const Vec3<Real>& view, Real surface_distance,
                       Real depth, const Vec3<Real>& ground, Real footprint, Real sun_share,
                       const Vec3<Real>& terrain, Real terrain_weight, ShadeWork& work) {
  const Real f = smooth01(depth * p.inv_full_depth);
  const Vec3<Real> s = view * surface_distance;
  const Vec3<Real> n = wave_normal(p, lattice, s.x, s.z, p.wave_strength * f, footprint);

  const Real cos_i = clamp01(-dot(view, n));
  const Real m = Real(1) - cos_i;
  const Real fresnel = Real(kFresnelF0) + Real(1 - kFresnelF0) * (m * m * m * m * m);
  Vec3<Real> reflected = view - n * (Real(2) * dot(view, n));
  reflected.y = std::abs(reflected.y);  // a steep wave must not reflect below the horizon
  Vec3<Real> sky = sky_radiance(p, skybox, reflected, sun_share);
  if (p.clouds) {  // from the surface point, to the sky
    sky = clouds_over_from(p, lattice, sky, s, surface_distance, reflected,
                           Real(limits::kMaxCameraRelativeDistance), work);
  }
  if (p.terrain_reflections) {  // the terrain the reflected ray meets hides the sky behind it
    sky = sky + (terrain - sky) * terrain_weight;
  }

  // Snell: t = eta v + (eta cos_i - sqrt(k)) n, k = 1 - eta^2 (1 - cos_i^2) > 0 from air.
  const Real eta = Real(kRelativeIndex);
  const Real k = Real(1) - eta * eta * (Real(1) - cos_i * cos_i);
  const Vec3<Real> t = view * eta + n * (eta * cos_i - std::sqrt(k));
  const Real path = depth / std::max(std::abs(t.y), Real(kMinTransmittedCosine));
  const Vec3<Real>& e = p.extinction_log2;
  const Vec3<Real> transmitted{exp2_det(-e.x * path), exp2_det(-e.y * path), exp2_det(-e.z * path)};

  // The sun's part past the terrain's cast shadow (x 1 without one: the same bits) and through
  // the cloud layer above the surface point, where there is one.
  const Vec3<Real> sun_part =
      p.sun * (Real(0.5) * std::max(Real(0), p.sun_direction.y)) * sun_share;
  const Vec3<Real> body_light =
      p.sky_light +
      (p.clouds ? sun_part * cloud_sun_share(p, lattice, s, footprint, work) : sun_part);
  const Vec3<Real> body = mix(p.shallow, p.deep, f) * body_light;
  const Vec3<Real> one{Real(1), Real(1), Real(1)};
  const Vec3<Real> under = ground * transmitted + body * (one - transmitted);
  const Real reflectivity = Real(0.3) + Real(0.7) * f;
  return mix(under, sky, fresnel * reflectivity);
}

template Vec3<float> wave_normal<float>(const ShadeParams<float>&, const NoiseLattice&, float,
                                        float, float, float);
template Vec3<double> wave_normal<double>(const ShadeParams<double>&, const NoiseLattice&, double,
                                          double, double, double);
template Vec3<float> shade_water<float>(const ShadeParams<float>&, const NoiseLattice&,
                                        const Skybox*, const Vec3<float>&, float, float,
                                        const Vec3<float>&, float, float, const Vec3<float>&, float,
                                        ShadeWork&);
template Vec3<double> shade_water<double>(const ShadeParams<double>&, const NoiseLattice&,
                                          const Skybox*, const Vec3<double>&, double, double,
                                          const Vec3<double>&, double, double, const Vec3<double>&,
                                          double, ShadeWork&);

}  // namespace relief
