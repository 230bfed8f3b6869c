// Stage 3: the octave-LOD fractal (§2.1 Eq. 1, §2.2 domain warping, §4.1 fractional octave).
//
//   H(x) - camera_y = (base - camera_y) + amplitude * sum_n  w_n a_n S(offset_n + f_n u + W_n)
//
// (heights are camera-relative: base - camera_y is formed once per frame in double)
// with u = d / horizontal_scale the camera-relative position in octave-0 lattice cells,
// f_n = r^k and a_n = r^(-kH) for octave k = k0 + n, offset_n from the octave table
// (octaves.h), S the interpolated lattice (interpolant.h), and the LOD weights of §4.1:
// w_n = 1 for the floor(nu) first octaves, nu - floor(nu) for the next one ("geomorphing"),
// 0 after. W_n is the domain-warp displacement in lattice cells of octave n (zero when
// warping is off), updated after each octave from the partial height h_n (the sum so far,
// without base and amplitude):
//   R_n      = R0 - h_n,                R0 = r^H                    (roughness)
//   rot_n+1  = normalise(c1 R_n + c2 + rot_n)                        (rotation vector)
//   t_n+1    = c3 h_n R_n / (R_n^2 + eps^2)   ~ c3 h_n / R_n         (translation)
//   W_n+1    = r (Rot(rot_n+1) W_n + t_n+1),  W_0 = t0, rot_0 = r0
// i.e. the paper's per-octave rotation/translation applied in the octave's own lattice
// coordinates, which the next octave scales by r. docs/paper-reading.md explains this reading
// of the garbled formulas: why R is R0 - H_i, why the transform moves the displacement W rather
// than the absolute position (the terrain must not change character with the distance from the
// origin), why the translation is in the current octave's cells (any coarser unit lets fine
// octaves feed back into the warp with a gain that grows like r^(n(1-H)): chaotic terrain),
// and the guard eps = kRoughnessGuard.
// The product f_n u is formed per octave either directly or exactly modulo P
// (octave_coordinates.h), as the frame chose in FbmParams::exact_coordinates; the full
// specification, with worked numbers, is docs/terrain-spec.md.
#pragma once

#include <cstdint>
#include <span>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/lattice.h"
#include "core/stage_params.h"

namespace relief {

// height[k] = H - camera_y at camera-relative (dx[k], dz[k]) with octave count nu[k], for k in
// range.
// Precondition: finite inputs; nu in [0, N] is the meaningful range (nu >= N sums every
// octave, nu <= 0 none). Output finite.
// The work done: points evaluated and octaves summed over them (a fractional octave counts
// as one).
struct FbmWork {
  std::uint64_t points = 0;
  std::uint64_t octaves = 0;
};

// `mask`: evaluate only where it is non-zero (heights elsewhere are 0: no consumer reads them,
// core/vertex_culling.h); empty: everywhere.
template <class Real>
FbmWork evaluate_fbm(const FbmParams<Real>& params, const NoiseLattice& lattice, IndexRange range,
                     std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                     std::span<const std::uint8_t> mask, std::span<Real> height);

// One point of evaluate_fbm with the parameters of `plan` (rounded for this call), for tests
// and tools.
template <class Real>
Real fbm_height(const TerrainPlan& plan, Real dx, Real dz, Real nu);

}  // namespace relief
