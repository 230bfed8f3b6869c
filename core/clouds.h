// The cloud layer (docs/stages.md, "Clouds"; castledragmire's and Miller's fractal cloud
// layers): sky.clouds fills the heights [bottom, top] with cloud whose density over (x, z) is
// domain-warped fBm of the terrain's own noise lattice. A path through the layer (the view ray
// up to the surface or the sky, or a point's ray toward the sun) crosses the band over a
// length L; the density read at its middle point D gives the optical depth
// tau = density x D x L, and the layer lets e^-tau of the light behind it through
// (Beer-Lambert). The ground truth reads D at cloud_steps points along the path instead
// (the midpoint rule), which measures what the one point leaves out.
//
// Density (at camera-relative x, z, of a pixel whose footprint there is `footprint`):
//   warp: w = (S(x, z; warp offsets 0, 1), S(x, z; 2, 3)) at the largest octave's cells;
//   n = sum_i a_i fade_i S(o_i + (x, z) / scale_i + 2^i warp w), fade_i = clamp(2 - 2
//   footprint / cell_i, 0, 1): an octave whose cell is under the footprint only aliases, so it
//   fades out between half a cell and a whole one (the dithering noise's rule, shade.cc);
//   D = clamp((n - threshold) sharpness, 0, 1), then mean + (D - mean) fade_0: where even the
//   largest octave is under the footprint the layer holds its mean density E[D].
// S is sample_lattice<kCubic> of core/interpolant.h. A path's point is read at a footprint of
// at least kCloudSpanFootprint of the horizontal span it stands for (clouds.cc,
// path_density), so a long slanted path does not read one cell's all-or-nothing.
//
// Domains: the path's vertical direction is floored at kCloudMinSlope in magnitude (its sign
// kept), so both crossings t = (h - y0) / dy are finite; every length is capped at `end` (at
// most kMaxCameraRelativeDistance), so tau, D and the coordinates stay finite (limits.h,
// sky.clouds); exp2_det clamps its argument. Never NaN or infinity.
#pragma once

#include "core/lattice.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

inline constexpr double kCloudMinSlope = 1e-4;
// The share of a path's horizontal span that widens its footprint (clouds.cc, path_density).
inline constexpr double kCloudSpanFootprint = 0.25;

// Where a path from height y0 (camera-relative) along a unit direction of vertical
// component dy, from 0 to `end`, lies inside the layer: from `start` over `length` (0: it
// misses the layer).
template <class Real>
struct CloudPath {
  Real start;
  Real length;
};

template <class Real>
CloudPath<Real> cloud_path(const ShadeParams<Real>& params, Real y0, Real dy, Real end);

// The layer's density D in [0, 1] at camera-relative (x, z), for a footprint `footprint`
// (world units) there.
template <class Real>
Real cloud_density(const ShadeParams<Real>& params, const NoiseLattice& lattice, Real x, Real z,
                   Real footprint, ShadeWork& work);

// The share of the sun's light that passes the layer on its way to the camera-relative point
// `position`, whose pixel's footprint is `footprint`: 1 where its ray misses the layer.
template <class Real>
Real cloud_sun_share(const ShadeParams<Real>& params, const NoiseLattice& lattice,
                     const Vec3<Real>& position, Real footprint, ShadeWork& work);

// `radiance` (already fogged) seen along unit `d` from the camera up to distance `end`,
// through the layer: radiance x e^-tau + the layer's own light x (1 - e^-tau), that light
// fogged over the distance to the path's middle (sky.h).
template <class Real>
Vec3<Real> clouds_over(const ShadeParams<Real>& params, const NoiseLattice& lattice,
                       const Vec3<Real>& radiance, const Vec3<Real>& d, Real end, ShadeWork& work);

// The same along unit `d` from the camera-relative point `origin`, which the camera sees
// `origin_distance` away (the water's reflected ray from its surface: water.h): the footprint
// and the fog's distance count from the camera. clouds_over is this from the camera (origin
// 0, distance 0), to the bit.
template <class Real>
Vec3<Real> clouds_over_from(const ShadeParams<Real>& params, const NoiseLattice& lattice,
                            const Vec3<Real>& radiance, const Vec3<Real>& origin,
                            Real origin_distance, const Vec3<Real>& d, Real end, ShadeWork& work);

}  // namespace relief
