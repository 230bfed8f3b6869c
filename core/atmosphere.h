// The atmosphere (docs/stages.md, "Atmosphere"): the sun's light scattered once by air whose
// density falls exponentially with height, seen along a view ray (in-scattering) and the light
// of the surface behind it dimmed on the way (transmittance). Bruneton & Neyret 2008 integrate
// the same single scattering numerically over a spherical shell into precomputed tables; over
// flat ground, with the sun's rays straight lines of a fixed slope, it has a closed form, so
// every pixel evaluates it exactly, with no table whose bits depend on the build.
//
// Density rho(y) = exp(-y / H) relative to height 0. A view ray from the camera (height y0,
// density rho0) along unit d with mu = d.y reaches distance T. With tau(t) the air's column
// along the ray up to t and the sun's column above a point S(t) = H rho(t) / mu_s, the light
// scattered toward the camera per unit of a coefficient beta with extinction beta_e is
//   I = integral_0^T rho(t) exp(-beta_e (tau(t) + S(t))) dt,
// and the substitution u = rho(t) (dt = -H du / (mu u)) turns the integrand into one
// exponential of u: with A = beta_e S(0) and B = beta_e (tau(T) + S(T)),
//   I = tau(T) (e^-A - e^-B) / (B - A) = tau(T) e^-min(A, B) phi(|A - B|),
// phi(z) = (1 - e^-z) / z, which stays in (0, 1] for z >= 0 and never cancels (a series below
// z = 1/16). The column itself is tau(T) = rho0 T phi(mu T / H) (the same phi, for either sign).
// The sun's rays and a ray toward the sky to infinity take the slope (mu + sqrt(mu^2 + 4 c^2))
// / 2 of their sine of elevation mu (0 below the horizon), c^2 = 2 H / (pi R) for a ground of
// radius R = 6371 km: 1 / that is Chapman's grazing function sqrt(pi X / 2) erfcx(mu
// sqrt(X / 2)), X = R / H, with erfcx(x) ~ 2 / (sqrt(pi) (x + sqrt(x^2 + 4 / pi))): the
// column of a spherical shell, exact at the horizon (sqrt(pi R / (2 H)) scale heights) and the
// zenith, within 5.7% between them for H = 8 km (tests/core/atmosphere_test.cc).
//
// Radiance: the surface times e^(-beta_e tau(T)) plus the sun (lighting's, times
// sky.atmosphere.intensity) times (beta_R P_R(cos) + beta_M P_M(cos)) I per channel, with
// Rayleigh's phase P_R = 3 (1 + cos^2) / (16 pi) and Cornette & Shanks's haze phase
// P_M = 3 (1 - g^2) (1 + cos^2) / (8 pi (2 + g^2) (1 + g^2 - 2 g cos)^(3/2)); the constants are
// folded into ShadeParams per frame (core/atmosphere_plan.h), the exponentials are exp2_det.
//
// Domains (every value finite, never NaN): distances above kMaxCameraRelativeDistance are
// taken as it (a background ray is that long: the limit of the air below the horizon). The
// column is formed from the denser end of the ray, tau = rho_dense T phi(|mu T / H|)
// (T phi(|w|) <= min(T, H / |mu|), whatever the heights), the sun's column above the end as
// rho_dense (H / mu_s) (rho_end / rho_dense); where either would pass kMaxOpticalDepth (1e20),
// rho_dense is lowered until the larger one is 1e20: the two keep their ratio, which sets the
// in-scattered light of such an opaque ray (I -> e^-A / (beta_e (1 + S_end / tau))).
#pragma once

#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

inline constexpr double kMaxOpticalDepth = 1e20;
inline constexpr double kLog2e = 1.4426950408889634;  // 1 / ln 2: e^x = 2^(x log2 e)
inline constexpr double kLn2 = 0.6931471805599453;
inline constexpr double kGrowthSeriesLimit = 0.0625;  // phi's series below |z| = 1/16
// phi's Taylor coefficients (-1)^k / (k + 1)!, k = 0 ... 8, evaluated by Horner's rule.
inline constexpr int kGrowthTerms = 9;
inline constexpr double kGrowthSeries[kGrowthTerms] = {1.0,        -1.0 / 2,     1.0 / 6,
                                                       -1.0 / 24,  1.0 / 120,    -1.0 / 720,
                                                       1.0 / 5040, -1.0 / 40320, 1.0 / 362880};

// phi(z) = (1 - e^-z) / z given e = e^-z (exp2_det's), for finite z: below |z| = 1/16 its
// Taylor series to z^8 (the next term, z^9 / 10!, is 4e-18 < 2^-57 of 1 there), else the
// quotient (z != 0 there; |1 - e| loses at most log2(16) = 4 bits to cancellation).
template <class Real>
Real column_growth(Real z, Real e);

// The surface at camera-relative distance `distance` along unit `d` (radiance) as the camera
// sees it through the air: dimmed, plus the light the air scatters toward the camera.
template <class Real>
Vec3<Real> atmosphere_over(const ShadeParams<Real>& params, const Vec3<Real>& radiance,
                           const Vec3<Real>& d, Real distance);

// The light the whole air along unit `d` scatters toward the camera: a ray to infinity at the
// grazing slope sqrt(max(mu, 0)^2 + c^2) (below the horizon, the horizon's). No sun disc
// (sky.cc adds it).
template <class Real>
Vec3<Real> atmosphere_sky(const ShadeParams<Real>& params, const Vec3<Real>& d);

}  // namespace relief
