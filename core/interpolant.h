// The auxiliary function S(x) of §2.1: the noise lattice extended to the plane by periodic
// interpolation. The paper uses the GPU's bilinear filtering; Relief offers three fade curves
// applied to the lattice values:
//   linear  fade(t) = t                      C0 (the paper's bilinear texture fetch)
//   cubic   fade(t) = t^2 (3 - 2t)           C1 (the cubic Hermite basis h01)
//   quintic fade(t) = t^3 (t (6t - 15) + 10) C2 (Perlin's improved fade)
// All three weights lie in [0, 1], so S is a convex combination of four lattice values: it
// passes through them and never leaves [min, max] of the lattice. That convexity is what makes
// the fBm amplitude bound (height_bounds.h) exact rather than guessed.
#pragma once

#include <cmath>
#include <string_view>

#include "core/lattice.h"

namespace relief {

enum class Interpolant { kLinear, kCubic, kQuintic };

template <Interpolant kKind, class Real>
constexpr Real fade(Real t) {
  if constexpr (kKind == Interpolant::kLinear) {
    return t;
  } else if constexpr (kKind == Interpolant::kCubic) {
    return t * t * (Real(3) - Real(2) * t);
  } else {
    return t * t * t * (t * (t * Real(6) - Real(15)) + Real(10));
  }
}

// d fade / dt, for analytic gradients of S.
template <Interpolant kKind, class Real>
constexpr Real fade_slope(Real t) {
  if constexpr (kKind == Interpolant::kLinear) {
    return Real(1);
  } else if constexpr (kKind == Interpolant::kCubic) {
    return Real(6) * t * (Real(1) - t);
  } else {
    return Real(30) * t * t * (t - Real(1)) * (t - Real(1));
  }
}

template <class Real>
constexpr Real fade(Interpolant kind, Real t) {
  switch (kind) {
    case Interpolant::kLinear:
      return fade<Interpolant::kLinear>(t);
    case Interpolant::kCubic:
      return fade<Interpolant::kCubic>(t);
    case Interpolant::kQuintic:
      return fade<Interpolant::kQuintic>(t);
  }
  return t;
}

// p mod P for a power-of-two period P, in [0, P]: p * (1/P) is exact (power of two) and so is
// its floor; p - P k is exact by Sterbenz's lemma except for p in (-P/2, 0), where it rounds
// like p + P and may round up to P itself (the caller masks the index, so P wraps to 0). The
// result is small for every finite p, so the integer conversion that follows cannot overflow
// however far the coordinate is from the origin.
template <class Real>
Real wrap_period(Real p, Real period, Real inv_period) {
  return p - period * std::floor(p * inv_period);
}

// The lattice cell holding (px, pz): its corner indices and the position inside it, in [0, 1).
template <class Real>
struct LatticeCell {
  int i0, j0, i1, j1;
  Real fx, fz;
};

template <class Real>
LatticeCell<Real> locate_cell(const NoiseLattice& lattice, Real px, Real pz) {
  const Real period = Real(lattice.size);
  const Real inv_period = Real(1) / period;  // exact: P is a power of two
  const Real wx = wrap_period(px, period, inv_period);
  const Real wz = wrap_period(pz, period, inv_period);
  const Real fx = std::floor(wx);
  const Real fz = std::floor(wz);
  LatticeCell<Real> cell;
  cell.i0 = static_cast<int>(fx) & lattice.mask;
  cell.j0 = static_cast<int>(fz) & lattice.mask;
  cell.i1 = (cell.i0 + 1) & lattice.mask;
  cell.j1 = (cell.j0 + 1) & lattice.mask;
  cell.fx = wx - fx;
  cell.fz = wz - fz;
  return cell;
}

// S(px, pz): the lattice interpolated at lattice coordinates (px, pz), with period P in both
// axes. Lerps are written a + w (b - a) so that w = 0 returns a exactly (S passes through the
// lattice values bit for bit). The operation order is the specification: the SIMD and GLSL ports to
// come follow it literally.
template <Interpolant kKind, class Real>
Real sample_lattice(const NoiseLattice& lattice, Real px, Real pz) {
  const LatticeCell<Real> c = locate_cell(lattice, px, pz);
  const Real tx = fade<kKind>(c.fx);
  const Real tz = fade<kKind>(c.fz);
  const Real v00 = lattice.at(c.i0, c.j0);
  const Real v10 = lattice.at(c.i1, c.j0);
  const Real v01 = lattice.at(c.i0, c.j1);
  const Real v11 = lattice.at(c.i1, c.j1);
  const Real bottom = v00 + tx * (v10 - v00);
  const Real top = v01 + tx * (v11 - v01);
  return bottom + tz * (top - bottom);
}

// S and its gradient (dS/dpx, dS/dpz) at (px, pz): the operations of sample_lattice for the
// value, plus the fade slopes.
template <Interpolant kKind, class Real>
Real sample_lattice_gradient(const NoiseLattice& lattice, Real px, Real pz, Real& dpx, Real& dpz) {
  const LatticeCell<Real> c = locate_cell(lattice, px, pz);
  const Real tx = fade<kKind>(c.fx);
  const Real tz = fade<kKind>(c.fz);
  const Real v00 = lattice.at(c.i0, c.j0), v10 = lattice.at(c.i1, c.j0);
  const Real v01 = lattice.at(c.i0, c.j1), v11 = lattice.at(c.i1, c.j1);
  const Real bottom = v00 + tx * (v10 - v00);
  const Real top = v01 + tx * (v11 - v01);
  const Real slope_bottom = v10 - v00, slope_top = v11 - v01;
  dpx = fade_slope<kKind>(c.fx) * (slope_bottom + tz * (slope_top - slope_bottom));
  dpz = fade_slope<kKind>(c.fz) * (top - bottom);
  return bottom + tz * (top - bottom);
}

template <class Real>
Real sample_lattice(const NoiseLattice& lattice, Interpolant kind, Real px, Real pz) {
  switch (kind) {
    case Interpolant::kLinear:
      return sample_lattice<Interpolant::kLinear>(lattice, px, pz);
    case Interpolant::kCubic:
      return sample_lattice<Interpolant::kCubic>(lattice, px, pz);
    case Interpolant::kQuintic:
      return sample_lattice<Interpolant::kQuintic>(lattice, px, pz);
  }
  return Real(0);
}

constexpr std::string_view interpolant_name(Interpolant kind) {
  switch (kind) {
    case Interpolant::kLinear:
      return "linear";
    case Interpolant::kCubic:
      return "cubic";
    case Interpolant::kQuintic:
      return "quintic";
  }
  return "quintic";
}

}  // namespace relief
