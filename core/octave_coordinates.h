// The lattice coordinate of each octave of Eq. 1, formed so that its fraction keeps the
// precision of the stage's type at every octave a scene allows.
//
// Octave n samples S at offset_n + g_n d + W_n (fbm.h), d the camera-relative position in world
// units and g_n = r^k / horizontal_scale, the double nearest that quotient (octaves.h). The
// product g_n d can be huge: with a small H the amplitude LOD sums fine octaves far from the
// camera (r = 2, H = 0.05, 24 octaves: 2^24 cells; per field up to 2^64). Formed as
// float(float(d / scale) r^k), its rounding error is |g_n d| 2^-23 cells: at 2^24 the octave
// is lattice noise and the float heights were off from double by hundreds of world units. Only
// the product modulo P matters (S is periodic), so it can be formed exactly:
//
//   exact form:  g_n = sum of pieces (three floats hold a double exactly, one double does),
//                each product d * piece = p + e exactly (Dekker's two-product with Veltkamp's
//                split: correctly rounded + - * only, no FMA, so every target and GLSL agree),
//                every p and e reduced modulo P exactly (wrap_period), and the reduced terms
//                summed smallest first with their rounding errors carried aside (two-sum):
//                one rounding of a number below 2P in all, whatever |g_n d| is.
//   direct form: (d * (1 / scale)) * r^k, two roundings of size |g_n d| 2^-24 each: as
//                accurate as the exact form while |g_n d| <= P, and four times cheaper.
//
// The frame decides the form per octave, from the farthest valid vertex that sums the octave
// (octave_reach, a maximum over stage 2's outputs: the same for every split of the rows and
// independent of the frame's skips): direct where g_n * reach_n <= P, exact elsewhere. The
// default scene needs only the direct form.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>

#include "core/grid_buffers.h"
#include "core/interpolant.h"
#include "core/limits.h"
#include "core/stage_params.h"

namespace relief {

// Float needs three pieces to hold a double's 53 bits (24 + 24 + 5), double one.
template <class Real>
inline constexpr int kScalePieces = std::is_same_v<Real, float> ? 3 : 1;

// Veltkamp's split a = hi + lo exactly, hi and lo of at most half the significand each, so
// that products of halves are exact. Valid while the splitter times |a| is finite.
template <class Real>
inline void split_halves(Real a, Real& hi, Real& lo) {
  constexpr Real kSplitter = std::is_same_v<Real, float> ? Real(4097) : Real(134217729);
  const Real t = kSplitter * a;  // 2^12 + 1, 2^27 + 1
  hi = t - (t - a);
  lo = a - hi;
}

// a * b - product exactly, from the halves of a and b (Dekker 1971).
template <class Real>
inline Real product_error(Real a_hi, Real a_lo, Real b_hi, Real b_lo, Real product) {
  return ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

// g as kScalePieces<Real> values of Real, largest first, whose sum is g exactly (three floats
// hold a double's 53 bits: 24 + 24 + 5), and their halves for the two-products.
template <class Real>
struct ScalePieces {
  Real piece[3] = {}, hi[3] = {}, lo[3] = {};
};

template <class Real>
inline ScalePieces<Real> split_scale(double g) {
  ScalePieces<Real> s;
  double rest = g;
  for (int q = 0; q < kScalePieces<Real>; ++q) {
    s.piece[q] = Real(rest);
    rest -= double(s.piece[q]);  // exact: rest and its rounding share their leading bits
    split_halves(s.piece[q], s.hi[q], s.lo[q]);
  }
  return s;
}

// a + b - sum exactly, sum = a + b rounded (Knuth's two-sum: any magnitudes).
template <class Real>
inline Real sum_error(Real a, Real b, Real sum) {
  const Real b_virtual = sum - a;
  const Real a_virtual = sum - b_virtual;
  return (a - a_virtual) + (b - b_virtual);
}

// g d mod P in [0, P], the exact form above. `piece`, `piece_hi`, `piece_lo`: the pieces of
// g, largest first, and their halves; d_hi, d_lo the halves of d. Each term is wrapped
// (exact), added to the running sum with its rounding error carried aside (two-sum), and the
// sum wrapped again (exact: it is not negative); the carry, a few ulp(P), is added once at the
// end: one rounding in all.
template <class Real>
inline Real exact_scaled_mod(const Real* piece, const Real* piece_hi, const Real* piece_lo, Real d,
                             Real d_hi, Real d_lo, Real period, Real inv_period) {
  Real sum = Real(0), carry = Real(0);
  const auto add = [&](Real term) {
    const Real wrapped = wrap_period(term, period, inv_period);
    const Real total = sum + wrapped;
    carry = carry + sum_error(sum, wrapped, total);
    sum = wrap_period(total, period, inv_period);
  };
  for (int q = kScalePieces<Real> - 1; q >= 0; --q) {
    const Real product = d * piece[q];
    add(product_error(d_hi, d_lo, piece_hi[q], piece_lo[q], product));
    add(product);
  }
  return wrap_period(sum + carry, period, inv_period);
}

// The farthest camera-relative extent, max(|dx|, |dz|) in world units, of a valid vertex that
// sums octave n (nu > n), for n < kMaxOctaves.
struct OctaveReach {
  std::array<double, limits::kMaxOctaves> extent{};

  void merge(const OctaveReach& other);
};

// The finest octave a point summing nu octaves reaches (fbm.h sums octave n where n < nu):
// ceil(nu) - 1, octave 0 for nu <= 1, the last table entry for nu past it (or NaN, from a
// scene that skipped validation: fbm.cc then sums every octave).
int finest_octave(double nu);

// Per octave the farthest extent of any point summing it, from the farthest per finest octave
// summed: a point summing octave n sums every coarser one (a running maximum from the fine
// octaves down).
OctaveReach running_reach(const OctaveReach& by_finest);

template <class Real>
OctaveReach octave_reach(IndexRange range, std::span<const Real> dx, std::span<const Real> dz,
                         std::span<const Real> nu, std::span<const std::uint8_t> valid);

// Sets each octave's form for a frame whose vertices reach `reach`: direct where
// g_n * reach_n <= P (both forms are then within a few ulp(P) of the exact product), exact
// elsewhere. The decision is made in double from the plan's g_n.
template <class Real>
void choose_coordinate_forms(const TerrainPlan& plan, const OctaveReach& reach,
                             FbmParams<Real>& params);

}  // namespace relief
