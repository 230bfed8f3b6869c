// Stage 8 in shading.mode = gradient (docs/stages.md, "Gradient shading"): castledragmire's
// height-to-colour gradient, lit per vertex (Gouraud shading) instead of per pixel.
//
// Albedo: the gradient's colour at the pixel's height, piecewise linear between its stops
// (ShadeParams::gradient_*; heights relative to the camera, like the pixel's). The seed colours
// vertices; here the gradient is read per pixel from the interpolated height, so a band's edge
// is a line on the ground rather than a smear across whole triangles whose size grows with
// the distance. In stop order, each segment i whose lower stop lies at or below h sets
//   t = h >= height[i + 1] ? 1 : min(1, (h - height[i]) inv_span[i])
//   colour = color[i] + (color[i + 1] - color[i]) t
// (the last such segment wins; below the first stop, color[0]). A step (two stops at one
// height, inv_span 0) therefore gives its upper colour from its height on.
//
// Light (Gouraud): the seed lights each vertex from its normal and lets the triangle
// interpolate. Stage 5 writes each vertex's Lambert term max(0, n . sun)
// (core/vertex_transform.h) and stage 7 interpolates it (`lambert`); the hemispherical light
// mix(ground, sky, 1/2 + n.y / 2) is affine in n.y, so interpolating n.y (the normal as
// resolved, not renormalised) interpolates it exactly as well. Per pixel:
//   albedo (sun lambert share + mix(ground, sky, (1/2 + ny / 2) sky_share) + ambient)
// with `share` the sun disc's visible share (1 without cast shadows) and `sky_share` the sky's
// open share (1 without sky light: sky_horizons.h). No specular term: the
// seed's lighting has none, and a per-vertex highlight only flickers across triangles.
#pragma once

#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

template <class Real>
Vec3<Real> gradient_albedo(const ShadeParams<Real>& params, Real relative_height);

template <class Real>
Vec3<Real> gouraud_light(const ShadeParams<Real>& params, const Vec3<Real>& albedo, Real lambert,
                         Real ny, Real sun_share, Real sky_share);

}  // namespace relief
