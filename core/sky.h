// Sky and distance fog (stage 8): a zenith-to-horizon gradient with a sun disc and halo where
// no terrain covers the pixel, and fog toward the horizon colour over every surface; or, where
// params.atmosphere is set, the sky and the aerial perspective of core/atmosphere.h (the
// gradient's colours and the fog's density are then not read).
#pragma once

#include "core/skybox.h"
#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

// Radiance of the sky in unit direction `d`: the gradient by elevation (horizon colour below
// the horizon, sqrt-shaped toward the zenith above it), or where params.skybox is set the
// skybox's faces (skybox.h; `skybox` must then be given), plus the sun disc with a smooth edge
// (20 x the sun's radiance) and a halo ((1 + cos)/2)^32 around it (over a skybox only where
// params.skybox_sun is set). The disc is scaled by `disc_share` in [0, 1]: the share of it the
// terrain leaves in view where the direction is the sun glint of a water surface in a cast
// shadow (water.h); the halo is the sky's own light and stays. 1 (the default) changes no bit.
template <class Real>
Vec3<Real> sky_radiance(const ShadeParams<Real>& params, const Skybox* skybox, const Vec3<Real>& d,
                        Real disc_share = Real(1));

// The fog colour seen along unit direction `d`: the horizon, warmer toward the sun; under the
// atmosphere the air's light along the whole ray (atmosphere_over of black at
// kMaxCameraRelativeDistance).
template <class Real>
Vec3<Real> fog_color(const ShadeParams<Real>& params, const Vec3<Real>& d);

// Exponential fog: the fraction 1 - exp(-density distance) of the fog colour, computed with
// exp2_det. distance >= 0.
template <class Real>
Vec3<Real> apply_fog(const ShadeParams<Real>& params, const Vec3<Real>& radiance,
                     const Vec3<Real>& d, Real distance);

}  // namespace relief
