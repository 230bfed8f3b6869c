// Cast shadows (docs/stages.md, "Cast shadows"): the terrain's horizon toward the sun, per frame,
// on a clipmap of height samples, and each pixel's share of the sun disc above it.
//
// A ray from a ground point toward the sun leaves the terrain's shadow when it passes above
// every height between the point and the sun; in the vertical plane through the sun's azimuth
// that is when the sun's elevation exceeds the horizon's: the largest elevation, seen from the
// point, of the terrain toward the sun. Along a line of samples in that plane the largest
// elevation of the samples beyond each one is the slope to its neighbour on the upper convex
// hull of those samples, and one sweep from the sun's end of the line keeps that hull (each
// sample pushed and popped once): the exact horizon of every sample of the line in time linear
// in its length (the 1D horizon sweep behind Timonen & Westermann 2010's horizon maps; the
// castledragmire seed's max-height skip is the hull's pop: a sample below the hull is never
// looked at again).
//
// The samples: `levels` square grids of N x N heights (a clipmap), rows along the sun's
// horizontal direction, level L spaced 2^L times level 0 and centred on the camera, each
// anchored to a world-space lattice of its spacing (so a moving camera reuses the same ground
// points: no swimming); laid out from the camera alone (shadow_geometry), built by a frame
// only where its pixels read them (shadow_level_range). A level's heights are stage 3's
// fractal and sketch at the level's octave count (the frame's LOD rule at the level's spacing)
// through the frame's own kernels. A row's sweep continues past its level's edge into the
// coarser levels (their samples beyond it, interpolated between their rows), up to the
// farthest an occluder can be: the terrain's whole height range climbed at the slope of the
// disc's lower edge, capped at the far plane's corner.
//
// Per sample the sweep stores the horizon's slope `tangent` (rise over run toward the sun) and
// the reciprocal of the run to the sample that sets it, `inv_distance`. A pixel (sun_visibility.h)
// reads its level's four samples around it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene.h"

namespace relief {

inline constexpr int kMaxShadowLevels = 24;

// The levels' layout, from the camera alone: level 0's spacing, the number of levels, and the
// half extent they cover.
struct ShadowGeometry {
  double spacing = 1;
  int levels = 1;
  double extent = 0;
};
ShadowGeometry shadow_geometry(const CameraFrame& camera, int viewport_height, int resolution);

// The levels a frame of `scene` can build: 0 without shadows and sky light, on a planet, or
// with the sun set and no sky light (the memory estimate's, pipeline/job_memory.h; a frame
// builds those its pixels reach).
int shadow_cache_levels(const Scene& scene);

// Derived once per frame in double (docs/stages.md, "Cast shadows", "Sky light"). The cache
// serves cast shadows (`enabled`) and sky light (`sky`, core/sky_horizons.h) alike.
struct ShadowPlan {
  bool enabled = false;  // cast shadows
  bool sky = false;      // sky light
  // The sun is below the horizon by more than its radius: every pixel is in the shadow of the
  // ground ahead (no cache is built).
  bool sun_set = false;
  int resolution = 0;  // N: samples per side of each level
  int levels = 0;
  double axis_x = 1, axis_z = 0;  // unit horizontal direction toward the sun
  double spacing[kMaxShadowLevels]{};
  // Camera-relative (u, v) of sample (0, 0) of each level: u along the axis, v = its left.
  double origin_u[kMaxShadowLevels]{}, origin_v[kMaxShadowLevels]{};
  double nu[kMaxShadowLevels]{};  // octaves summed at each level (stage 3's count)
  double reach = 0;               // the horizontal distance an occluder can lie from a pixel
  double sky_reach = 0;           // the same for sky light (sky_horizons.h)
  double sin_elevation = 0, cos_elevation = 1;
  double sin_radius = 0;  // of the sun disc's angular radius (sky.sun_disc_deg)
  // tan(elevation - radius) and tan(elevation + radius): a horizon below the first lights the
  // whole disc, one above the second hides it (each clamped to +-1e30 at +-90 degrees).
  double lit_tangent = 0, dark_tangent = 0;
  // The frame's water (terrain.water_level above some terrain, the camera above it): the
  // level's samples are raised to its surface (raise_to_water_surface), camera-relative.
  bool water = false;
  double water_level = 0;
  // water.reflect_terrain: the reflected rays march over the levels' heights
  // (water_reflection.h), which are then built whether or not the sun is up.
  bool reflections = false;
};

// Camera-relative u of the last sample of a level's rows (ShadowPlan in double, ShadowParams
// in Real): the one expression the sweep and the level range both use, so that a row's end
// and the start of its continuation compare exactly.
template <class Params>
auto level_last_u(const Params& p, int level) {
  using Value = std::remove_cvref_t<decltype(p.origin_u[0])>;
  return p.origin_u[level] + Value(p.resolution - 1) * p.spacing[level];
}

// From the scene's lighting and the frame: the sun, the levels (shadow_geometry, anchored to
// the world lattice of their spacings about the camera), their octave counts and the
// occluders' reach. Disabled where lighting.shadows, lighting.sky_occlusion and the water's
// reflections (water.reflect_terrain with water in the frame) are off, or on a planet.
ShadowPlan make_shadow_plan(const Scene& scene, const FramePlan& frame);

// How far from the camera the cache's samples that sum each octave lie (octave_coordinates.h):
// each level's square at its corners, widened by 1e-6 for the positions' rounding, so that the
// cache's stage 3 picks coordinate forms from its own extent, not the frame's grid.
OctaveReach shadow_octave_reach(const ShadowPlan& plan);

// The plan rounded once to the precision the stages run in.
template <class Real>
struct ShadowParams {
  std::int32_t enabled = 0, sun_set = 0;  // cast shadows; the sun set (ShadowPlan)
  std::int32_t sky = 0;                   // sky light (sky_horizons.h)
  std::int32_t skip_lit = 1;              // FrameSkips::lit_shadows (sun_visibility.h)
  // The levels a frame builds and reads, [first_level, end_level) (shadow_level_range): the
  // finer ones lie nearer than any pixel, the coarser ones past every pixel and its occluders.
  std::int32_t first_level = 0, end_level = 0;
  std::int32_t resolution = 0, levels = 0;
  Real axis_x = 1, axis_z = 0;
  Real spacing[kMaxShadowLevels]{}, inv_spacing[kMaxShadowLevels]{};
  // The band along a level's edge where its share fades into the next level's: N / 32 samples.
  Real blend_samples = 1, inv_blend_samples = 1;
  Real origin_u[kMaxShadowLevels]{}, origin_v[kMaxShadowLevels]{};
  Real nu[kMaxShadowLevels]{};
  Real reach = 0, sky_reach = 0;
  Real sin_elevation = 0, cos_elevation = 1, sin_radius = 0;
  Real lit_tangent = 0, dark_tangent = 0;
  std::int32_t water = 0;  // ShadowPlan::water
  Real water_level = 0;
  std::int32_t reflections = 0;  // ShadowPlan::reflections
};

template <class Real>
ShadowParams<Real> make_shadow_params(const ShadowPlan& plan);

// The sample coordinates (fi, fj) of camera-relative (u, v) (the sun's frame) in level
// `level`, and whether they lie inside the level's cells, [0, N - 1) both: a pixel's lookup
// (sun_visibility.h, sky_horizons.h) reads the four samples around it there.
template <class Real>
bool level_coordinates(const ShadowParams<Real>& p, int level, Real u, Real v, Real& fi, Real& fj) {
  const Real last = Real(p.resolution - 1);
  fi = (u - p.origin_u[level]) * p.inv_spacing[level];
  fj = (v - p.origin_v[level]) * p.inv_spacing[level];
  return fi >= Real(0) && fi < last && fj >= Real(0) && fj < last;
}

// A pixel's value from the cache at camera-relative (u, v) (the sun's frame): `at(level, fi,
// fj)` in the finest level from `first_level` whose square holds the point (the squares nest:
// it holds the point in every coarser level too); within the band of `blend_samples` along
// that square's edge faded linearly into the next coarser level's value, so that a pixel
// passing from one level to the next sees no step, and the squares, which follow the camera a
// spacing at a time, move no edge at once. False where no level holds the point (NaN
// coordinates, or beyond the coarsest level).
template <class Real, class At>
bool blended_level_value(const ShadowParams<Real>& p, Real u, Real v, At&& at, Real& value) {
  Real fi = 0, fj = 0;
  int level = p.first_level;
  while (level < p.end_level && !level_coordinates(p, level, u, v, fi, fj)) {
    ++level;
  }
  if (level >= p.end_level) {
    return false;
  }
  value = at(level, fi, fj);
  const Real last = Real(p.resolution - 1);
  const Real edge = std::min(std::min(fi, fj), std::min(last - fi, last - fj));
  if (edge < p.blend_samples && level + 1 < p.end_level &&
      level_coordinates(p, level + 1, u, v, fi, fj)) {
    const Real coarse = at(level + 1, fi, fj);
    value = coarse + (value - coarse) * (edge * p.inv_blend_samples);
  }
  return true;
}

// The cache: per level N rows of N samples, row-major, level after level, for the levels
// [first_level, end_level) a frame builds.
template <class Real>
struct SunHorizonCache {
  int resolution = 0, first_level = 0, end_level = 0;
  AlignedVector<Real> height;        // camera-relative (stage 3's)
  AlignedVector<Real> tangent;       // of the horizon toward the sun (cast shadows)
  AlignedVector<Real> inv_distance;  // 1 / the horizontal run to the sample that sets it
  AlignedVector<Real> sky;           // the sky left open (sky light; sky_horizons.h)

  // `sun`, `sky`: whether the frame reads the sun's horizons and the sky's openness.
  void allocate(int n, int first, int end, bool sun, bool sky);
  std::size_t index(int level, int row, int column) const {
    return (std::size_t(level - first_level) * resolution + row) * resolution + column;
  }
};

// Bounds of the Chebyshev distance max(|u|, |v|), in the sun's frame about the camera, of every
// point of every triangle one of whose vertices in rows [rows.begin, rows.end) is drawn (kDraw
// in `need`, vertex_culling.h) and valid: per such vertex its own distance less (plus) the
// largest Chebyshev distance to a grid neighbour it shares a triangle with ((i +- 1, j),
// (i, j +- 1), (i + 1, j + 1), (i - 1, j - 1)), widened by 1e-4 of it for the pixels'
// interpolation in float; and the lowest camera-relative height of those triangles (their
// vertices'). Empty (nearest +inf, farthest 0, lowest +inf) where there is none.
struct DrawnExtent {
  double nearest = HUGE_VAL;
  double farthest = 0;
  double lowest = HUGE_VAL;

  void merge(const DrawnExtent& o) {
    nearest = std::min(nearest, o.nearest);
    farthest = std::max(farthest, o.farthest);
    lowest = std::min(lowest, o.lowest);
  }
};
template <class Real>
DrawnExtent drawn_extent(const ShadowPlan& plan, const GridLayout& layout, RowRange rows,
                         std::span<const Real> dx, std::span<const Real> dz,
                         std::span<const Real> height, std::span<const std::uint8_t> valid,
                         std::span<const std::uint8_t> need);

// The same over a mesh's triangles (GeoMipMapping, core/heightfield/field_mesh.h): triangles
// [first, end) of `indices` (3 vertex indices each into the streams). The Chebyshev distance is
// convex, so a triangle's points lie no farther than its farthest vertex and no nearer than its
// nearest vertex less its longest edge in that norm; widened by that edge too (a covered pixel
// may lie a little outside its snapped triangle) and by 1e-4 as above; the lowest height its
// vertices'. Every vertex of the list is drawn and valid (mesh_domain).
template <class Real>
DrawnExtent mesh_drawn_extent(const ShadowPlan& plan, std::span<const std::uint32_t> indices,
                              std::size_t first, std::size_t end, std::span<const Real> dx,
                              std::span<const Real> dz, std::span<const Real> height);

// The levels a frame with pixels within `drawn` builds, [first, end): from the finest whose
// square reaches the nearest pixel (every finer square lies nearer than any pixel; with water,
// the nearest water surface a pixel's ray can meet in front of its ground) to the one
// past the level whose row ends reach the occluders beyond the farthest pixel's level, and
// the next coarser level too (a pixel near its level's edge reads it: sun_visibility.h). The
// squares are tested with a margin of 1e-4 for the float test of a pixel against a square;
// with reflections, to the coarsest level (their rays reach past every pixel). None
// (first == end) where `drawn` is empty.
struct LevelRange {
  int first = 0, end = 0;
};
LevelRange shadow_level_range(const ShadowPlan& plan, const DrawnExtent& drawn);

// The camera-relative positions of row `row` of level `level` (N values each), for stage 3's
// kernels, and their octave count.
template <class Real>
void shadow_row_positions(const ShadowParams<Real>& params, int level, int row, std::span<Real> dx,
                          std::span<Real> dz, std::span<Real> nu);

// Where the frame has water (p.water), each of `heights` below the water level raised to it:
// the cache then holds the horizons of the ground and of the water surface, the one seen by
// the sun where it lies higher. A point on the surface (the glint, core/water.h) sees the sun
// over the terrain around the water, not over the lake bed beneath it, whose samples would
// set a horizon close below the point that the point's lift cannot undo (sun_visibility.h:
// the horizon of a sample lowered by lift / run to the same occluder understates a raised
// point's horizon, which farther, higher terrain may set). Ground under the water then takes
// the share of the surface above it: the light reaches it through that surface. Land changes
// only within a cell of the shore, where a point's four samples include raised ones, or a
// sample's tangent plane (sky light) reads one; elsewhere the raised samples lie below a point
// at or above the water and set no horizon the sun, higher than its radius, stands under.
template <class Real>
void raise_to_water_surface(const ShadowParams<Real>& p, std::span<Real> heights) {
  if (p.water == 0) {
    return;
  }
  for (Real& h : heights) {
    h = std::max(h, p.water_level);
  }
}

// The work of the sweep (docs/stages.md, "Skipped work").
struct HorizonWork {
  std::uint64_t samples = 0;       // samples of the levels swept
  std::uint64_t continuation = 0;  // samples of coarser levels read past a row's end
  std::uint64_t popped = 0;        // hull points dropped: never looked at again

  HorizonWork& operator+=(const HorizonWork& o) {
    samples += o.samples;
    continuation += o.continuation;
    popped += o.popped;
    return *this;
  }
};

// The horizons of rows [rows.begin, rows.end) of level `level`, from the heights of that level
// and of the coarser ones (all written before): toward the sun for cast shadows (where the
// sun is up), and toward both ends of the row for sky light (its first two of four
// directions, sky_horizons.h).
template <class Real>
HorizonWork sweep_sun_horizons(const ShadowParams<Real>& params, int level, RowRange rows,
                               SunHorizonCache<Real>& cache);

}  // namespace relief
