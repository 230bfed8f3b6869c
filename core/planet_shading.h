// Stage 8 on a planet (§4.1's spherical domain, docs/planet.md): what the plane's shading assumes
// (a horizontal water surface, open water below the horizon) made right for the sphere. The water
// pass shades in the local frame of the point it looks at (its up the sphere's radial direction),
// and the background ray meets the water sphere, the datum sphere (beyond the horizon: fog) or
// neither (the sky).
#pragma once

#include <cmath>

#include "core/det_math.h"
#include "core/vec3.h"

namespace relief {

// `v` in the frame whose up is the unit vector `up` (the rotation taking up to (0, 1, 0) about
// up x (0, 1, 0)); v itself where up points straight down (the antipode, never in view).
template <class Real>
Vec3<Real> to_local_frame(const Vec3<Real>& v, const Vec3<Real>& up) {
  const Real c = up.y;
  if (!(c > Real(-0.999))) {
    return v;  // the division's domain: 1 + c >= 0.001
  }
  const Vec3<Real> w{-up.z, Real(0), up.x};  // up x (0, 1, 0)
  const Vec3<Real> wv{w.y * v.z - w.z * v.y, w.z * v.x - w.x * v.z, w.x * v.y - w.y * v.x};
  const Vec3<Real> wwv{w.y * wv.z - w.z * wv.y, w.z * wv.x - w.x * wv.z, w.x * wv.y - w.y * wv.x};
  const Real k = Real(1) / (Real(1) + c);
  return Vec3<Real>{v.x + wv.x + wwv.x * k, v.y + wv.y + wwv.y * k, v.z + wv.z + wwv.z * k};
}

// Distance along the unit ray `d` (camera-relative, double) to the near side of the sphere
// centred at (0, -D, 0) with c = (D - r)(D + r) > 0 (the camera outside it); < 0 for a miss.
inline double planet_sphere_hit(const double d[3], double center_distance, double c) {
  const double b = d[1] * center_distance;  // d . (camera - centre), negative when descending
  const double disc = b * b - c;
  if (!(c > 0.0) || !(b < 0.0) || !(disc >= 0.0)) {
    return -1.0;
  }
  return c / (-b + std::sqrt(disc));  // the stable root; domain: -b > 0
}

// The direction the sky gradient reads for a ray that misses the planet: its elevation
// measured from the limb instead of the horizontal, (alpha - alpha_limb) / (pi - alpha_limb)
// of a right angle (alpha the ray's nadir angle), in the ray's own azimuth. On the surface
// (alpha_limb = pi/2) that is the elevation itself; from orbit the limb glows with the
// horizon's colour and the space above it darkens toward the zenith's.
template <class Real>
Vec3<Real> planet_sky_direction(const double d[3], double limb_angle) {
  const double horizontal = std::sqrt(d[0] * d[0] + d[2] * d[2]);
  const double alpha = atan2_det(horizontal, -d[1]);
  const double span = 3.14159265358979323846 - limb_angle;  // > 0: limb_angle <= pi/2
  const double t = alpha > limb_angle ? (alpha - limb_angle) / span : 0.0;
  double sine, cosine;
  sin_cos_det(t * 1.5707963267948966, sine, cosine);
  // Domain of the divisions: horizontal > 0; straight up or down the azimuth is any.
  const double hx = horizontal > 0.0 ? d[0] / horizontal : 0.0;
  const double hz = horizontal > 0.0 ? d[2] / horizontal : -1.0;
  return Vec3<Real>{Real(hx * cosine), Real(sine), Real(hz * cosine)};
}

// What a planet frame's background ray meets (planet_background, core/shade.cc), in double:
// the water sphere (when water is on), else the datum sphere (the ground beyond the horizon;
// below the horizontal where the camera is below the datum), else the sky.
enum class PlanetBackgroundKind { kSky, kWater, kGround };

template <class Real>
struct PlanetBackgroundRay {
  PlanetBackgroundKind kind = PlanetBackgroundKind::kSky;
  Vec3<Real> up{};   // water: the sphere's unit normal at the hit
  Real surface = 0;  // water: the distance to the hit
  Vec3<Real> sky{};  // sky: the direction the sky gradient reads (planet_sky_direction)
};

// `ray`: the view ray in double (any length >= 1: the frame's forward is a unit vector and the
// image-plane offsets are perpendicular to it); the planet's fields of ShadeParams.
template <class Real>
PlanetBackgroundRay<Real> planet_background_ray(const double ray[3], bool water_enabled,
                                                double center_distance, double water_c,
                                                double datum_c, double limb_angle) {
  PlanetBackgroundRay<Real> out;
  const double length = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
  const double unit[3] = {ray[0] / length, ray[1] / length, ray[2] / length};  // length >= 1
  const double D = center_distance;
  if (water_enabled) {
    const double t = planet_sphere_hit(unit, D, water_c);
    if (t >= 0.0) {
      // The local up there: the hit relative to the centre, normalised (its length is the
      // water sphere's radius, > 0).
      const double hit[3] = {t * unit[0], t * unit[1] + D, t * unit[2]};
      const double radius = std::sqrt(hit[0] * hit[0] + hit[1] * hit[1] + hit[2] * hit[2]);
      out.kind = PlanetBackgroundKind::kWater;
      out.up = Vec3<Real>{Real(hit[0] / radius), Real(hit[1] / radius), Real(hit[2] / radius)};
      out.surface = Real(t);
      return out;
    }
  }
  // The ground beyond the horizon; a camera below the datum (in a valley, or inside the
  // planet) has the plane's rule: below the horizontal.
  const bool ground = datum_c > 0.0 ? planet_sphere_hit(unit, D, datum_c) >= 0.0 : unit[1] < 0.0;
  if (ground) {
    out.kind = PlanetBackgroundKind::kGround;
    return out;
  }
  out.sky = planet_sky_direction<Real>(unit, limb_angle);
  return out;
}

}  // namespace relief
