// §4.1's spherical domain, per-frame part (docs/planet.md): "the planar basis domain is warped
// around a sphere after the vertices have been projected".
//
// Camera-centred geometry: the camera stands at altitude a = camera y - terrain.base_height
// above its sub-camera point; the planet's centre is camera-relative (0, -(R + a), 0). A
// camera-relative base-domain point (dx, dz), what stage 2 writes and stage 3 evaluates, is an
// arc offset: the sphere point at arc length rho = |(dx, dz)| from the sub-camera point in the
// direction of (dx, dz) (azimuthal equidistant), central angle theta = rho / R.
//
// Stage 2 intersects each vertex's projector ray with a "grid sphere" (the datum, radius R,
// or just below the camera when the camera is below the datum: the plane's projection plane
// rule) for the plain projected grid on the sphere, theta_true(alpha) of the ray's nadir angle
// alpha; and maps alpha linearly onto [theta_lo, theta_h] for equal-angle sampling from
// orbit, theta_eq(alpha). The frame blends them by b = smoothstep(begin, end, a): one b per
// frame (no seam), continuous in the altitude (no popping).
#pragma once

#include <cstdint>

#include "core/camera.h"
#include "core/height_bounds.h"
#include "core/projector.h"
#include "core/scene/scene.h"
#include "core/stage_param_fields.h"

namespace relief {

struct PlanetPlan {
  bool enabled = false;        // a planet scene (terrain.planet with radius > 0)
  bool visible = false;        // false: the camera is below every terrain, or deep inside
  double radius = 0;           // R
  double altitude = 0;         // a = camera y - base_height
  double center_distance = 0;  // D = R + a, the camera's distance from the centre
  double grid_radius = 0;      // Rg <= R: the sphere the projector rays are intersected with
  double grid_c = 0;           // (D - Rg)(D + Rg) = ag (2 Rg + ag), ag = D - Rg > 0
  double theta_limb = 0;       // central angle of the grid sphere's limb seen from the camera
  double alpha_h = 0;          // nadir angle of that limb
  double theta_h = 0;          // the horizon: no terrain beyond this central angle
  double alpha_lo = 0;         // smallest nadir angle of the grid's rays
  double theta_lo = 0;         // theta_true(alpha_lo)
  double blend = 0;            // b: 0 plain projected grid, 1 equal angles
  double elevation_min = 0, elevation_max = 0;  // height bounds - base_height
};

// What the frame needs before its projector: everything but alpha_lo and theta_lo.
PlanetPlan make_planet_plan(const TerrainSettings& terrain, const CameraFrame& camera,
                            const HeightBounds& bounds);

// The projector of a planet frame: the slab lowered by the curvature drop out to theta_h, no
// regional refinement (the refinement's regions are planar); then alpha_lo and theta_lo from
// its coverage hull, in `planet`.
Projector make_planet_projector(const CameraFrame& camera, const HeightBounds& bounds,
                                double base_height, PlanetPlan& planet);

// The near hit of a ray of nadir angle alpha with the grid sphere, as a central angle (plain
// mode), in double; the limb's angle for rays that miss it.
double planet_theta_true(const PlanetPlan& planet, double alpha);

// The values stages 2, 4 (the bend) and 8 read, rounded once (members: stage_param_fields.h).
template <class Real>
struct PlanetParams {
  RELIEF_DECLARE_FIELDS(RELIEF_PLANET_PARAMS_FIELDS)
};

template <class Real>
PlanetParams<Real> make_planet_params(const PlanetPlan& plan);

}  // namespace relief
