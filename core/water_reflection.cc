#include "core/water_reflection.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/clouds.h"
#include "core/det_math.h"
#include "core/interpolant.h"
#include "core/limits.h"
#include "core/sky.h"
#include "core/sun_visibility.h"
#include "core/water.h"

namespace relief {

namespace {

// Rays rising within 1e-6 of the vertical move less than a millionth of their length across
// the ground: they stay above the surface point they leave (the step's division's domain).
constexpr double kMinHorizontalSpeed = 1e-6;
// A jump to a block's exit lands a thousandth of a cell past it, inside the next block.
constexpr double kBlockExitNudge = 1e-3;

template <class Real>
Real interpolate(Real a, Real b, Real f) {
  return a + (b - a) * f;
}

// The ray in the cache's frame: (u, v) along and across the sun's azimuth (sun_horizons.h),
// the height y, each linear in the distance t along the ray.
template <class Real>
struct CacheRay {
  Real u, v, y;     // at t = 0
  Real du, dv, dy;  // per unit of t
  Real speed;       // sqrt(du^2 + dv^2): horizontal distance per unit of t
};

// The finest level from `level` or from the ones finer down to p.first_level that holds
// (u, v), and its sample coordinates; -1 where none does (the squares nest: a finer level
// holding a point holds it only if the next finer than the current one does, and a coarser
// one holds whatever a finer one holds).
template <class Real>
int holding_level(const ShadowParams<Real>& p, int level, Real u, Real v, Real& fi, Real& fj) {
  while (level > p.first_level && level_coordinates(p, level - 1, u, v, fi, fj)) {
    --level;
  }
  while (level < p.end_level && !level_coordinates(p, level, u, v, fi, fj)) {
    ++level;
  }
  return level < p.end_level ? level : -1;
}

// The level's bilinear surface at sample coordinates (fi, fj) inside it.
template <class Real>
Real surface_height(const SunHorizonCache<Real>& c, int level, Real fi, Real fj) {
  const int i = int(fi), j = int(fj);  // floor: both >= 0
  const Real f = fi - Real(i), g = fj - Real(j);
  const Real* h00 = &c.height[c.index(level, j, i)];
  const Real* h10 = &c.height[c.index(level, j + 1, i)];
  return interpolate(interpolate(h00[0], h00[1], f), interpolate(h10[0], h10[1], f), g);
}

// The gap between the ray's height and the surface at t, and the level holding the point
// (-1: the ray has left the cache; the gap is then meaningless).
template <class Real>
Real gap_at(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c, const CacheRay<Real>& r,
            Real t, int& level, ReflectionWork& work) {
  Real fi = 0, fj = 0;
  level =
      holding_level(p, level < 0 ? p.first_level : level, r.u + r.du * t, r.v + r.dv * t, fi, fj);
  if (level < 0) {
    return Real(0);
  }
  ++work.lookups;
  return (r.y + r.dy * t) - surface_height(c, level, fi, fj);
}

// The distance along the ray from sample coordinates (fi, fj) of `level` to the edge of the
// square [low_i, high_i] x [low_j, high_j] that holds them. In sample units the ray moves
// (du, dv) / spacing per unit of t; the exit is the nearer of the edges ahead along each axis
// (an axis it does not move along never exits). speed >= 1e-6: one of the two moves, so the
// distance is finite and >= 0.
template <class Real>
Real square_exit(const ShadowParams<Real>& p, const CacheRay<Real>& r, int level, Real fi, Real fj,
                 Real low_i, Real low_j, Real high_i, Real high_j) {
  const Real si = r.du * p.inv_spacing[level], sj = r.dv * p.inv_spacing[level];
  Real exit = Real(HUGE_VAL);
  if (si > Real(0)) {
    exit = std::min(exit, (high_i - fi) / si);
  } else if (si < Real(0)) {
    exit = std::min(exit, (low_i - fi) / si);
  }
  if (sj > Real(0)) {
    exit = std::min(exit, (high_j - fj) / sj);
  } else if (sj < Real(0)) {
    exit = std::min(exit, (low_j - fj) / sj);
  }
  return exit;
}

// `exit` plus `nudge` (> 0), at least the next value past it: where the distance is so large
// beside the nudge that the sum rounds back to it, the ray still moves on.
template <class Real>
Real past(Real exit, Real nudge) {
  const Real t = exit + nudge;
  return t > exit ? t : std::nextafter(exit, Real(HUGE_VAL));
}

}  // namespace

template <class Real>
bool trace_reflection(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c,
                      const HeightBlockMaxima<Real>& m, const Vec3<Real>& start,
                      const Vec3<Real>& direction, ReflectionHit<Real>& hit, ReflectionWork& work) {
  ++work.rays;
  CacheRay<Real> r;
  r.u = start.x * p.axis_x + start.z * p.axis_z;
  r.v = start.z * p.axis_x - start.x * p.axis_z;
  r.y = start.y;
  r.du = direction.x * p.axis_x + direction.z * p.axis_z;
  r.dv = direction.z * p.axis_x - direction.x * p.axis_z;
  r.dy = std::max(Real(0), direction.y);
  r.speed = std::sqrt(r.du * r.du + r.dv * r.dv);  // argument >= 0

  int level = p.first_level;
  Real t = 0;
  // The last distance known to have the ray at or above the surface; none yet: a surface
  // point within a cell of the shore, where the raised cache stands above the water, sees
  // the shore at once (t = 0, no refinement).
  Real above = Real(-1);
  const bool vertical = !(r.speed >= Real(kMinHorizontalSpeed));
  const Real last = Real(p.resolution - 1);
  // The budget: a grazing ray may step every cell of every level it crosses (with no
  // skip), half cells where below a cell's top; it ends a ray that would not (kMaxReflectionSteps
  // at N = 64, more for a finer cache).
  const int budget = std::max(kMaxReflectionSteps, 64 * p.resolution);
  for (int step = 0;; ++step) {
    if (step >= budget) {
      ++work.left;
      return false;
    }
    const Real y = r.y + r.dy * t;
    if (y > m.top) {  // rising, above every height: nothing more to meet
      ++work.above;
      return false;
    }
    Real fi = 0, fj = 0;
    level = holding_level(p, level, r.u + r.du * t, r.v + r.dv * t, fi, fj);
    if (level < 0) {
      ++work.left;
      return false;
    }
    const Real spacing = p.spacing[level];
    if (!vertical && y >= m.level_top[level]) {
      // Above the level and every finer one: it stays so to the level's edge (rising).
      above = t + square_exit(p, r, level, fi, fj, Real(0), Real(0), last, last);
      t = past(above, Real(kBlockExitNudge) * spacing / r.speed);
      ++work.levels;
      continue;
    }
    // The largest block the ray stands above (its edges' samples, and the finer levels inside
    // it): it stays so to the block's exit, where it jumps. A tier's block lies inside the
    // next's, whose maximum is no lower: the first tier it is not above ends the search.
    const int i = int(fi), j = int(fj);
    int tier = -1;
    while (!vertical && tier + 1 < m.tiers &&
           y >= m.at(tier + 1, level, j >> (kReflectionBlockLog2 + tier + 1),
                     i >> (kReflectionBlockLog2 + tier + 1))) {
      ++tier;
    }
    if (tier >= 0) {
      const int shift = kReflectionBlockLog2 + tier, size = 1 << shift;
      const Real low_i = Real(i >> shift << shift), low_j = Real(j >> shift << shift);
      above = t + square_exit(p, r, level, fi, fj, low_i, low_j, std::min(last, low_i + Real(size)),
                              std::min(last, low_j + Real(size)));
      t = past(above, Real(kBlockExitNudge) * spacing / r.speed);
      ++work.skipped;
      continue;
    }
    ++work.lookups;
    const Real* h0 = &c.height[c.index(level, j, i)];
    const Real* h1 = &c.height[c.index(level, j + 1, i)];
    const Real f = fi - Real(i), g = fj - Real(j);
    const Real surface = interpolate(interpolate(h0[0], h0[1], f), interpolate(h1[0], h1[1], f), g);
    if (y - surface < Real(0)) {
      break;  // crossed between `above` and t
    }
    if (vertical) {  // it stays over this point, rising: nothing to meet
      ++work.above;
      return false;
    }
    if (y >= std::max(std::max(h0[0], h0[1]), std::max(h1[0], h1[1]))) {
      // Above the cell's four samples, which bound its bilinear surface: to the cell's exit.
      above = t + square_exit(p, r, level, fi, fj, Real(i), Real(j), Real(i + 1), Real(j + 1));
      t = past(above, Real(kBlockExitNudge) * spacing / r.speed);
    } else {
      above = t;
      t = t + Real(0.5) * spacing / r.speed;
    }
  }
  // Bisection between `above` (gap >= 0) and t (gap < 0).
  if (above >= Real(0)) {
    Real below = t;
    for (int k = 0; k < kReflectionRefinements; ++k) {
      const Real mid = Real(0.5) * (above + below);
      int mid_level = level;
      const Real mid_gap = gap_at(p, c, r, mid, mid_level, work);
      if (mid_level >= 0 && mid_gap < Real(0)) {
        below = mid;
        level = mid_level;
      } else {
        above = mid;
      }
    }
    t = below;
  }
  // The surface's gradient at the hit, from its cell (in the sun's frame, then in x and z:
  // u = x a_x + z a_z, v = z a_x - x a_z).
  Real fi = 0, fj = 0;
  level = holding_level(p, level, r.u + r.du * t, r.v + r.dv * t, fi, fj);
  if (level < 0) {
    ++work.left;
    return false;
  }
  const int i = int(fi), j = int(fj);
  const Real f = fi - Real(i), g = fj - Real(j);
  const Real* h00 = &c.height[c.index(level, j, i)];
  const Real* h10 = &c.height[c.index(level, j + 1, i)];
  const Real dh_du = interpolate(h00[1] - h00[0], h10[1] - h10[0], g) * p.inv_spacing[level];
  const Real dh_dv = interpolate(h10[0] - h00[0], h10[1] - h00[1], f) * p.inv_spacing[level];
  hit.distance = t;
  hit.point = start + direction * t;
  hit.point.y = interpolate(interpolate(h00[0], h00[1], f), interpolate(h10[0], h10[1], f), g);
  hit.slope_x = dh_du * p.axis_x - dh_dv * p.axis_z;
  hit.slope_z = dh_du * p.axis_z + dh_dv * p.axis_x;
  ++work.hits;
  return true;
}

template <class Real>
ReflectionRay<Real> reflection_ray(const ShadeParams<Real>& p, const NoiseLattice& lattice, Real dx,
                                   Real height, Real dz, Real depth) {
  ReflectionRay<Real> ray;
  // The view ray and its surface point as terrain_radiance and shade_water form them
  // (shade.cc, water.cc): on the plane, height < level < 0, so view.y < 0.
  const Vec3<Real> position{dx, height, dz};
  const Vec3<Real> view = normalize_or(position, p.camera_forward);
  if (!(view.y < Real(0))) {
    return ray;
  }
  const Real surface = p.water_level / view.y;  // > 0
  const Real footprint = surface * p.pixel_angle / std::max(std::abs(view.y), Real(0.05));
  const Real f = smooth01(std::max(Real(0), depth) * p.inv_full_depth);
  // On the surface exactly: view.y (level / view.y) may round below the level, under the
  // cache's raised water, where the ray would meet the water it leaves.
  const Vec3<Real> start{view.x * surface, p.water_level, view.z * surface};
  const Vec3<Real> n = wave_normal(p, lattice, start.x, start.z, p.wave_strength * f, footprint);
  const Vec3<Real> reflected = view - n * (Real(2) * dot(view, n));
  // A wave tilted toward the eye sends the reflected ray lower than the flat mirror's (whose
  // elevation is -view.y), down to the horizon and, folded above it by water.cc, back up:
  // such a ray would meet the next wave, and marched over the terrain it finds the far shore
  // at the water's level, dark rims around every glint. The terrain's weight fades from 1
  // where the ray rises at least half the mirror's elevation to 0 where it is horizontal or
  // folded (the sky of water.cc there); an unperturbed ray, and every wave far away, where
  // water.h fades the waves out, keeps weight 1.
  ray.weight = smooth01(reflected.y / (Real(-0.5) * view.y));  // -view.y > 0
  ray.start = start;
  ray.surface = surface;
  ray.direction = normalize_or(reflected, Vec3<Real>{Real(0), Real(1), Real(0)});
  return ray;
}

template <class Real>
Real reflected_terrain(const ReflectionScene<Real>& s, const ReflectionRay<Real>& ray,
                       Vec3<Real>& radiance, ReflectionWork& work, ShadeWork& shade_work) {
  const ShadeParams<Real>& p = *s.shade;
  radiance = Vec3<Real>{0, 0, 0};
  if (!(ray.weight > Real(0))) {
    return Real(0);
  }
  const Vec3<Real>& start = ray.start;
  const Vec3<Real>& reflected = ray.direction;
  const Real surface = ray.surface;
  ReflectionHit<Real> hit;
  if (!trace_reflection(*s.levels, *s.cache, *s.maxima, start, reflected, hit, work)) {
    return Real(0);
  }
  // The hit as a pixel of its own: its normal and slope from the cache's cell, the texture's
  // footprint that of the whole path (isotropic), the sun's and the sky's shares from the
  // same cache where those effects are on.
  const Real path = surface + hit.distance;
  const Real pixel = path * p.pixel_angle;
  const Vec3<Real> normal = normalize_or(Vec3<Real>{-hit.slope_x, Real(1), -hit.slope_z},
                                         Vec3<Real>{Real(0), Real(1), Real(0)});
  PixelAttributes<Real> a{};
  a.dx = hit.point.x;
  a.dz = hit.point.z;
  a.height = hit.point.y;
  a.dx_ddx = pixel;
  a.dz_ddy = pixel;
  a.height_ddx = hit.slope_x * pixel;
  a.height_ddy = hit.slope_z * pixel;
  a.nx = normal.x;
  a.ny = normal.y;
  a.nz = normal.z;
  // |grad h|, bounded as stage 4 bounds it (a cache's slopes reach amplitude / spacing).
  a.slope = std::min(std::sqrt(hit.slope_x * hit.slope_x + hit.slope_z * hit.slope_z),
                     Real(limits::kMaxSlope));
  a.sun = Real(1);
  a.sky = Real(1);
  a.water_sun = Real(1);
  a.lambert = std::max(Real(0), dot(normal, p.sun_direction));
  if (s.sun != nullptr) {
    ShadowWork unused;
    a.sun = sun_visibility(*s.sun, *s.cache, hit.point.x, hit.point.y, hit.point.z, unused);
  }
  if (s.sky != nullptr) {
    SkyWork unused;
    a.sky = sky_visibility(*s.sky, *s.cache, hit.point.x, hit.point.z, unused);
  }
  radiance = lit_terrain(p, s.resources, a, hit.point, path, reflected, shade_work);
  if (p.fog_enabled) {  // along the reflected path, from the surface to the hit
    radiance = apply_fog(p, radiance, reflected, hit.distance);
  }
  if (p.clouds) {  // the cloud layer between the surface and the hit, where the path crosses it
    radiance = clouds_over_from(p, *s.resources.lattice, radiance, start, surface, reflected,
                                hit.distance, shade_work);
  }
  return ray.weight;
}

template <class Real>
Real reflected_terrain(const ReflectionScene<Real>& s, Real dx, Real height, Real dz, Real depth,
                       Vec3<Real>& radiance, ReflectionWork& work, ShadeWork& shade_work) {
  return reflected_terrain(s, reflection_ray(*s.shade, *s.resources.lattice, dx, height, dz, depth),
                           radiance, work, shade_work);
}

template bool trace_reflection<float>(const ShadowParams<float>&, const SunHorizonCache<float>&,
                                      const HeightBlockMaxima<float>&, const Vec3<float>&,
                                      const Vec3<float>&, ReflectionHit<float>&, ReflectionWork&);
template bool trace_reflection<double>(const ShadowParams<double>&, const SunHorizonCache<double>&,
                                       const HeightBlockMaxima<double>&, const Vec3<double>&,
                                       const Vec3<double>&, ReflectionHit<double>&,
                                       ReflectionWork&);
template ReflectionRay<float> reflection_ray<float>(const ShadeParams<float>&, const NoiseLattice&,
                                                    float, float, float, float);
template ReflectionRay<double> reflection_ray<double>(const ShadeParams<double>&,
                                                      const NoiseLattice&, double, double, double,
                                                      double);
template float reflected_terrain<float>(const ReflectionScene<float>&, const ReflectionRay<float>&,
                                        Vec3<float>&, ReflectionWork&, ShadeWork&);
template double reflected_terrain<double>(const ReflectionScene<double>&,
                                          const ReflectionRay<double>&, Vec3<double>&,
                                          ReflectionWork&, ShadeWork&);
template float reflected_terrain<float>(const ReflectionScene<float>&, float, float, float, float,
                                        Vec3<float>&, ReflectionWork&, ShadeWork&);
template double reflected_terrain<double>(const ReflectionScene<double>&, double, double, double,
                                          double, Vec3<double>&, ReflectionWork&, ShadeWork&);

}  // namespace relief
