// Terrain reflected in the water (docs/stages.md, "Reflections"; Miller's seed traces the
// reflected ray from the water surface over the terrain): per pixel whose view ray meets the
// water before its ground, the ray reflected about the wave normal (water.h) is marched from the
// surface point over the terrain's heights, the samples of the cast shadows' horizon cache
// (sun_horizons.h: nested square levels about the camera, spacing doubling level by level, each
// at the frame's level of detail for its spacing, so the reflection is as detailed as the
// ground seen at that distance). Where it meets the terrain, the reflected radiance is the
// terrain lit there (sun, cast shadow and sky light read from the same cache, the cloud layer's
// shadow), fogged along the reflected path and seen through the cloud layer on it; where it
// escapes, the sky of water.h.
//
// The march (castledragmire's max-height skipping): the reflected ray never descends (water.h
// folds it above the horizon), so once it stands above the largest height of a block of
// kReflectionBlock x kReflectionBlock cells it stays above it to the block's exit, which it
// jumps to without a height lookup; above the largest height of a level and the finer ones it
// jumps to the level's edge; above the largest height of every level it can meet nothing
// more (the blocks and tops: height_block_maxima.h). Elsewhere it compares its height with the
// bilinear surface of the finest level holding it: above the cell's four samples it jumps to
// the cell's exit, else it steps half a cell; a crossing is refined by bisection. A ray leaving
// the coarsest level (reflections build every level past the nearest water surface:
// shadow_level_range) or the step budget escapes. The surface is
// the cache's, raised to the water (raise_to_water_surface): a ray from the surface meets the
// shore, not the lake bed.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/height_block_maxima.h"
#include "core/shade.h"
#include "core/sky_horizons.h"
#include "core/sun_horizons.h"
#include "core/vec3.h"

namespace relief {

inline constexpr int kMaxReflectionSteps = 4096;  // steps a ray may take: at least this
inline constexpr int kReflectionRefinements = 8;  // bisections of a crossing: 1/512 cell

// The work of the reflected rays (docs/stages.md, "Skipped work").
struct ReflectionWork {
  std::uint64_t rays = 0;     // pixels whose reflected ray was marched
  std::uint64_t lookups = 0;  // bilinear height lookups (steps and bisections)
  std::uint64_t skipped = 0;  // blocks jumped over without a lookup
  std::uint64_t levels = 0;   // levels' squares crossed without a lookup
  std::uint64_t hits = 0;     // rays that met the terrain
  std::uint64_t above = 0;    // rays that rose above every height of the cache
  std::uint64_t left = 0;     // rays that left the cache or the step budget

  ReflectionWork& operator+=(const ReflectionWork& o) {
    rays += o.rays;
    lookups += o.lookups;
    skipped += o.skipped;
    levels += o.levels;
    hits += o.hits;
    above += o.above;
    left += o.left;
    return *this;
  }
};

// Where a reflected ray met the terrain: the distance along it, the camera-relative point and
// the surface's gradient there (d height / dx, d height / dz).
template <class Real>
struct ReflectionHit {
  Real distance = 0;
  Vec3<Real> point{};
  Real slope_x = 0, slope_z = 0;
};

// Marches the ray from camera-relative `start` along unit `direction` (direction.y >= 0) over
// the cache (`levels`: its layout, first_level and end_level those built). True with `hit`
// where it meets the terrain. Finite inputs.
template <class Real>
bool trace_reflection(const ShadowParams<Real>& levels, const SunHorizonCache<Real>& cache,
                      const HeightBlockMaxima<Real>& maxima, const Vec3<Real>& start,
                      const Vec3<Real>& direction, ReflectionHit<Real>& hit, ReflectionWork& work);

// What a pixel's reflection reads: the frame's stage 8 parameters and resources, the cache, its
// maxima, and the cast shadows' and sky light's parameters (null where off).
template <class Real>
struct ReflectionScene {
  const ShadeParams<Real>* shade = nullptr;
  ShadeResources resources;
  const ShadowParams<Real>* levels = nullptr;
  const SunHorizonCache<Real>* cache = nullptr;
  const HeightBlockMaxima<Real>* maxima = nullptr;
  const ShadowParams<Real>* sun = nullptr;
  const ShadowParams<Real>* sky = nullptr;
};

// A pixel's reflected ray: where it leaves the water surface, its unit direction, the surface's
// distance from the camera, and the terrain's weight (0: no ray to march).
template <class Real>
struct ReflectionRay {
  Vec3<Real> start{}, direction{};
  Real surface = 0;
  Real weight = 0;
};

// The ray of the pixel at camera-relative (dx, height, dz) with water depth `depth` (the first
// half of reflected_terrain below; simd/reflection_rays.h forms the same bits in vectors).
template <class Real>
ReflectionRay<Real> reflection_ray(const ShadeParams<Real>& params, const NoiseLattice& lattice,
                                   Real dx, Real height, Real dz, Real depth);

// The second half: the ray marched and its hit shaded, as below.
template <class Real>
Real reflected_terrain(const ReflectionScene<Real>& scene, const ReflectionRay<Real>& ray,
                       Vec3<Real>& radiance, ReflectionWork& work, ShadeWork& shade_work);

// The pixel at camera-relative (dx, height, dz) with water depth `depth`, its view ray meeting
// the water surface first (height < water level < 0, on the plane): the reflected ray's
// terrain radiance, fogged from the surface to the hit, into `radiance` and 1; where it
// escapes, 0 (radiance 0). shade_water mixes the sky toward the radiance by that weight.
template <class Real>
Real reflected_terrain(const ReflectionScene<Real>& scene, Real dx, Real height, Real dz,
                       Real depth, Vec3<Real>& radiance, ReflectionWork& work,
                       ShadeWork& shade_work);

}  // namespace relief
