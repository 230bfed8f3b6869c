// The bend of a planet frame (§4.1, docs/planet.md): each vertex's arc offset (dx, dz) and
// camera-relative height hc (= e - a, e the elevation above the datum) to its camera-relative
// position on the sphere, with no R-sized term cancelling (the camera-relative rule holds on
// the sphere too):
//   theta   = |(dx, dz)| / R
//   (px, pz) = (dx, dz) ((R + e) / R) sinc(theta)
//   py      = hc - drop,  drop = (R + e) 2 sin^2(theta / 2)
// R + e = D + hc, with D = R + a formed in double per frame. The normals of stage 4, computed
// in the unbent frame, are rotated into the bent one: the local frame at (theta, direction u)
// is the camera's rotated by theta about the horizontal axis perpendicular to u. sin and cos
// are core/det_math.h's, so every backend bends alike: the reference backends run this scalar
// code, the simd backend its Highway twin (simd/planet_bend.h), the GL backend bend.comp.
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/planet_plan.h"

namespace relief {

// Bent positions and drops of elements [range.begin, range.end); zeros where invalid.
template <class Real>
void bend_vertices(const PlanetParams<Real>& planet, IndexRange range, std::span<const Real> dx,
                   std::span<const Real> dz, std::span<const Real> height,
                   std::span<const std::uint8_t> valid, BentSpans<Real> out);

// Rotates the normals (nx, ny, nz) of elements [range.begin, range.end) into the bent frame.
template <class Real>
void bend_normals(const PlanetParams<Real>& planet, IndexRange range, std::span<const Real> dx,
                  std::span<const Real> dz, std::span<const std::uint8_t> valid, std::span<Real> nx,
                  std::span<Real> ny, std::span<Real> nz);

}  // namespace relief
