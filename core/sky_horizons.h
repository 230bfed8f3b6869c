// Sky light (docs/stages.md, "Sky light"): the share of the sky a point's surroundings leave
// open, from the terrain's horizons in four directions on the cast shadows' horizon cache
// (sun_horizons.h), and each pixel's share read from it.
//
// The hemispherical light (Scape's sky and ground colours, mixed by the normal) comes from the
// sky above the horizontal plane; its weight, 1/2 + n.y / 2, already counts what a tilted
// surface turns away from. Terrain rising above the surface's own tangent plane hides more.
// Seen from a horizontal surface, the sky between elevations e_p and e_h in one azimuth holds
// sin^2 e_h - sin^2 e_p of the cosine-weighted hemisphere (the integral of 2 sin a cos a da),
// and the sky above e_p holds cos^2 e_p of it; with e_p the elevation of the tangent plane
// toward the azimuth (0 where it falls away) and e_h the horizon's, the open part of the sky
// the plane leaves is cos^2 e_h / cos^2 e_p = (1 + tan^2 e_p) / (1 + tan^2 e_h), 1 where the
// horizon lies no higher than the plane: an even slope is wholly open, a valley floor between
// walls is not. The tangent plane is the level's surface (the central difference along the
// line); the octaves finer than a level's are left to the normal. The share is the mean over
// four azimuths, the cache's rows and columns toward both of their ends (horizon-based ambient
// occlusion, as Timonen & Westermann's horizon maps give it, on the grid the sweeps already
// run on): the rows' two in the sun's sweep (sweep_sun_horizons), the columns' two here. The
// four follow the sun's azimuth, as the cache's rows do: turning the sun turns where the
// azimuth is sampled, not what is sampled. Each sweep is the same linear-time hull sweep
// (horizon_lines.h), whose pops are the max-height skip of every ray of a line at once.
//
// Per sample, not per pixel: the openness varies over the scale of valleys and ridges, which
// the cache resolves (a sample spans about 7 pixels at N = 256). A pixel reads its level's four
// samples around it, bilinearly, blended into the next level near a level's edge as the sun's
// share is (sun_horizons.h, blended_level_value).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/grid_buffers.h"
#include "core/sun_horizons.h"

namespace relief {

// The horizon slope past which the sky's reach stops: terrain farther than the height range
// over this slope rises less than atan(1/32) = 1.8 degrees above any point, hiding at most
// 1 - 1 / (1 + 1/32^2) < 0.1% of the sky in its azimuth.
inline constexpr double kSkyReachTangent = 1.0 / 32.0;

// The open share of the sky in one azimuth above a horizon of slope `horizon`, over a surface
// whose tangent plane rises at slope `plane` toward it: (1 + p^2) / (1 + t^2) with
// p = max(0, plane) and t the horizon where t > p, else 1. Both are clamped to 1e6 first (a
// horizon within 6e-5 degrees of the zenith: 1e-12 of the sky, 0 to float's precision), so
// that the squares stay inside float; the divisor 1 + t^2 >= 1.
template <class Real>
Real sky_openness(Real horizon, Real plane) {
  const Real p = std::clamp(plane, Real(0), Real(1e6));
  if (!(horizon > p)) {
    return Real(1);
  }
  const Real t = std::min(horizon, Real(1e6));
  return (Real(1) + p * p) / (Real(1) + t * t);
}

// The columns' two directions of the sky's four, for columns [columns.begin, columns.end) of
// level `level`: adds their openness to the rows' two (sweep_sun_horizons, run before) and
// leaves the mean of the four in `cache.sky`.
template <class Real>
HorizonWork sweep_sky_columns(const ShadowParams<Real>& params, int level, RowRange columns,
                              SunHorizonCache<Real>& cache);

struct SkyWork {
  std::uint64_t pixels = 0;   // covered pixels looked up
  std::uint64_t open = 0;     // of those, with the whole sky open (share 1)
  std::uint64_t outside = 0;  // beyond the cache: open

  SkyWork& operator+=(const SkyWork& o) {
    pixels += o.pixels;
    open += o.open;
    outside += o.outside;
    return *this;
  }
};

// The open share of the sky at camera-relative (dx, dz), in [0, 1]. Precondition: params.sky,
// the cache swept in all four directions. Finite or NaN inputs (NaN: outside, 1).
template <class Real>
Real sky_visibility(const ShadowParams<Real>& params, const SunHorizonCache<Real>& cache, Real dx,
                    Real dz, SkyWork& work);

}  // namespace relief
