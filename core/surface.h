// Stage 4: the surface pass (§4.1, "additional properties ... derived in a second pass"):
// normals, slope and water depth at the grid vertices.
//
// Normals come from the neighbouring displaced vertices, not from analytic fBm gradients:
//  - they are the normals of the surface that is actually rasterised, so shading agrees with
//    the geometry at every LOD (an analytic gradient would show detail the mesh does not
//    have, and would need the chain rule through the domain warp);
//  - they work for the C0 interpolant, whose gradient jumps at lattice lines;
//  - they cost four reads per vertex instead of roughly doubling the cost of stage 3.
// Method: with tangents a = p(i+1) - p(i-1) and b = p(j+1) - p(j-1) (one-sided at borders and
// next to invalid vertices), solve  gx a_x + gz a_z = a_h,  gx b_x + gz b_z = b_h  for the
// height gradient g = (gx, gz); normal = normalise(-gx, 1, -gz), slope = |g| (the paper's
// |grad H|, §4.2). The projected grid is irregular, so this 2x2 solve replaces the usual
// cross product of a regular grid (same normal, plus the slope directly).
// Visible sides: where one side of a vertex faces the eye by a cosine below kSilhouetteFacing
// (a crest seen against what lies behind it), that side's half of the central difference
// weighs in proportion, and 1/32 once hidden; otherwise a silhouette's normal leans towards
// the hidden far slope and the silhouette is lit as that slope (1-px dark lines along ridges).
// Continuous as a side turns away; the plain central difference wherever both sides face the
// eye (docs/architecture.md, "Stage 4, operation by operation").
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/stage_params.h"

namespace relief {

template <class Real>
struct SurfaceInputs {
  std::span<const Real> dx;
  std::span<const Real> dz;
  std::span<const Real> height;
  std::span<const std::uint8_t> valid;
  // VertexNeed flags (vertex_culling.h): only kDraw vertices are computed (the others get the
  // invalid vertices' defaults); empty: every valid vertex.
  std::span<const std::uint8_t> need;
};

// Writes rows [rows.begin, rows.end) of `out`; reads rows begin - 1 .. end of `in`.
// Invalid and padding vertices get normal (0, 1, 0), slope 0, water depth 0.
// Division domains: each tangent is first divided by its largest component (when non-zero), a
// positive factor that keeps the products below near 1 at any scale; the 2x2 system is solved
// only when its determinant exceeds kMinTangentSine
// times the product of the tangents' base-plane lengths (else the one-axis least-norm
// gradient, or zero); the normal is formed without dividing by the determinant and scaled by
// its largest component before normalising, so no square overflows; slope = |g| is capped at
// kMaxSlope (a vertical wall for every consumer).
template <class Real>
void surface_pass(const SurfaceParams<Real>& params, RowRange rows, SurfaceInputs<Real> in,
                  SurfaceSpans<Real> out);

}  // namespace relief
