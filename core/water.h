// Water (§4.3): the surface at the water level over terrain lower than it.
//
// "A time-resolved normal map" perturbs the surface: three octaves of the terrain's noise
// lattice, each drifting in its own direction with time, gradients analytic, each faded out
// where the pixel's footprint exceeds half its wavelength (no aliasing sparkle far away).
// "The strength of the bump effect, the reflectivity and the color of the surface are
// modulated with the water depth": with f = smooth01(depth / full_depth), the bump strength
// and the reflectivity scale with f (reflectivity from 0.3 to 1), the body colour goes from
// shallow to deep. Fresnel (Schlick, F0 = 0.02) weighs the reflected sky (sun glints included)
// against the transmitted light. "Approximate the length [of the transmitted ray] by assuming
// a locally flat ground and computing a ray/plane intersection taking the interpolated
// per-pixel water depth into account": the refracted ray (Snell, 1 / 1.333) reaches flat
// ground `depth` below the surface after depth / |t_y|; the ground's radiance is attenuated by
// exp(-extinction length) per channel, and the water body's colour fills the rest.
#pragma once

#include "core/lattice.h"
#include "core/shade.h"
#include "core/skybox.h"
#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

// `view`: unit direction from the camera; `surface_distance`: distance along it to the water
// surface (> 0); `depth`: water depth below that point (>= 0; a large value for open water
// with no ground in view); `ground`: radiance of the lit ground; `footprint`: the pixel's
// size on the surface, world units.
// `lattice`: the terrain's noise lattice, which the waves reuse. The reflected sky is seen
// through the cloud layer where the scene has one (clouds.h; its sun glint so shadowed by the
// clouds), its work counted into `work`. `sun_share` in [0, 1]: the sun disc's share that the
// terrain leaves in view from the surface point (cast shadows, sun_visibility.h; 1 without
// them): it scales the sun glint (the reflected disc, not the sky's halo) and the sunlit part
// of the water body, as a cast shadow darkens the ground. `terrain`, `terrain_weight`: with
// water.reflect_terrain (params.terrain_reflections) the terrain the reflected ray meets
// (water_reflection.h) and 1, or 0 where it escapes: the reflected sky and clouds mixed toward
// it by the weight (x + (t - x) 0: the sky's bits); unread without reflections.
template <class Real>
Vec3<Real> shade_water(const ShadeParams<Real>& params, const NoiseLattice& lattice,
                       const Skybox* skybox, const Vec3<Real>& view, Real surface_distance,
                       Real depth, const Vec3<Real>& ground, Real footprint, Real sun_share,
                       const Vec3<Real>& terrain, Real terrain_weight, ShadeWork& work);

// The wave normal at camera-relative surface position (x, z), for bump strength `strength`.
template <class Real>
Vec3<Real> wave_normal(const ShadeParams<Real>& params, const NoiseLattice& lattice, Real x, Real z,
                       Real strength, Real footprint);

}  // namespace relief
