// Per-target body of simd/fbm.h: fbm_point of core/fbm.cc on a vector of points. Lanes whose
// octaves are done (n past their nu) keep their height and warp through masks, so each lane
// computes exactly what the scalar loop computes for its point; the vector stops at the first
// octave no needed lane sums.
#if defined(RELIEF_SIMD_FBM_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_FBM_INL_H_
#undef RELIEF_SIMD_FBM_INL_H_
#else
#define RELIEF_SIMD_FBM_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

#include "core/fbm.h"
#include "core/octave_coordinates.h"
#include "simd/fbm_lattice-inl.h"
#include "simd/lattice-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

// g_n d for octave n: direct or exact modulo P, as the frame chose (octave_coordinates.h).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ScaledCoordinate(D d, const FbmParams<float>& c, int n, V dist, V u, V d_hi, V d_lo) {
  if (!c.exact_coordinates[n]) {
    return hn::Mul(hn::Set(d, c.frequency[n]), u);
  }
  const V period = hn::Set(d, c.period);
  const V inv_period = hn::Set(d, c.inv_period);
  V sum = hn::Zero(d), carry = hn::Zero(d);
  const auto add = [&](V term) {
    const V wrapped = WrapPeriod(d, term, period, inv_period);
    const V total = hn::Add(sum, wrapped);
    carry = hn::Add(carry, SumError(sum, wrapped, total));
    sum = WrapPeriod(d, total, period, inv_period);
  };
  for (int q = kScalePieces<float> - 1; q >= 0; --q) {
    const V product = hn::Mul(dist, hn::Set(d, c.scale_piece[q][n]));
    add(ProductError(d_hi, d_lo, hn::Set(d, c.scale_piece_hi[q][n]),
                     hn::Set(d, c.scale_piece_lo[q][n]), product));
    add(product);
  }
  return WrapPeriod(d, hn::Add(sum, carry), period, inv_period);
}

// One vector of points; `need` selects the lanes to evaluate. Returns the heights (0 where
// not needed) and adds the octaves summed by needed lanes to `octaves`.
template <Interpolant kKind, class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V FbmVector(D d, const FbmParams<float>& c, const LatticeView& lattice, V dx, V dz, V nu,
                       M need, std::uint64_t& octaves) {
  const V one = hn::Set(d, 1.0f);
  const V zero = hn::Zero(d);
  const V ux = hn::Mul(dx, hn::Set(d, c.inv_scale));
  const V uz = hn::Mul(dz, hn::Set(d, c.inv_scale));
  V dx_hi, dx_lo, dz_hi, dz_lo;
  SplitHalves(d, dx, dx_hi, dx_lo);
  SplitHalves(d, dz, dz_hi, dz_lo);
  // §4.1: floor(nu) whole octaves (at most N), then one weighted by the fraction. Integers
  // below 2^24 compare exactly as floats.
  const V whole = hn::Floor(nu);
  const V count = hn::Set(d, float(c.count));
  const V full = hn::IfThenElse(hn::Lt(whole, count), whole, count);
  const V fraction = hn::Sub(nu, whole);
  V h = zero;
  V wx = hn::Set(d, c.t0x), wz = hn::Set(d, c.t0z);  // W_n, §2.2
  V rx = hn::Set(d, c.r0x), rz = hn::Set(d, c.r0z);  // rot_n, §2.2
  const V period = hn::Set(d, lattice.period);
  const V inv_period = hn::Set(d, lattice.inv_period);
  // §2.2: R_n, rot_{n+1}, t_{n+1} and W_{n+1} after a whole octave (core/fbm.cc), in the lanes
  // of `moves`.
  const auto warp = [&](M moves) {
    const V roughness = hn::Sub(hn::Set(d, c.roughness0), h);
    const V inv_roughness =
        hn::Div(roughness, hn::Add(hn::Mul(roughness, roughness), hn::Set(d, c.guard_sq)));
    const V vx = hn::Add(hn::Add(hn::Mul(hn::Set(d, c.c1x), roughness), hn::Set(d, c.c2x)), rx);
    const V vz = hn::Add(hn::Add(hn::Mul(hn::Set(d, c.c1z), roughness), hn::Set(d, c.c2z)), rz);
    const V length_sq = hn::Add(hn::Mul(vx, vx), hn::Mul(vz, vz));
    const M renormalise = hn::And(moves, hn::Gt(length_sq, hn::Set(d, c.min_rotation_sq)));
    const V inv_length = hn::Div(one, hn::Sqrt(length_sq));
    rx = hn::IfThenElse(renormalise, hn::Mul(vx, inv_length), rx);
    rz = hn::IfThenElse(renormalise, hn::Mul(vz, inv_length), rz);
    const V height_over_roughness = hn::Mul(h, inv_roughness);
    const V next_wx = hn::Add(hn::Sub(hn::Mul(rx, wx), hn::Mul(rz, wz)),
                              hn::Mul(hn::Set(d, c.c3x), height_over_roughness));
    const V next_wz = hn::Add(hn::Add(hn::Mul(rz, wx), hn::Mul(rx, wz)),
                              hn::Mul(hn::Set(d, c.c3z), height_over_roughness));
    const V lacunarity = hn::Set(d, c.lacunarity);
    wx = hn::IfThenElse(moves, hn::Mul(lacunarity, next_wx), wx);
    wz = hn::IfThenElse(moves, hn::Mul(lacunarity, next_wz), wz);
  };
  // S at octave n, every lane.
  const auto sample = [&](int n) {
    const V px = hn::Add(
        hn::Add(hn::Set(d, c.offset_x[n]), ScaledCoordinate(d, c, n, dx, ux, dx_hi, dx_lo)), wx);
    const V pz = hn::Add(
        hn::Add(hn::Set(d, c.offset_z[n]), ScaledCoordinate(d, c, n, dz, uz, dz_hi, dz_lo)), wz);
    return SampleLatticeWindowed<kKind>(d, lattice, period, inv_period, px, pz);
  };
  // First the octaves every needed lane sums whole, without masks: weight 1, and (1 a_n) S is
  // a_n S exactly.
  const V needed_full = hn::IfThenElse(need, full, count);
  const float fewest_full = hn::GetLane(hn::MinOfLanes(d, needed_full));
  const int whole_for_all = fewest_full > 0.0f ? static_cast<int>(fewest_full) : 0;
  const std::uint64_t needed_lanes = hn::CountTrue(d, need);
  const M every_lane = hn::FirstN(d, hn::Lanes(d));
  int n = 0;
  for (; n < whole_for_all; ++n) {
    h = hn::Add(h, hn::Mul(hn::Set(d, c.amplitude[n]), sample(n)));
    octaves += needed_lanes;
    if (c.warp && n + 1 < c.count) {
      warp(every_lane);
    }
  }
  // Then lane by lane: the fractional octave, and lanes whose nu ends earlier.
  for (; n < c.count; ++n) {
    const V octave = hn::Set(d, float(n));
    const M below = hn::Lt(octave, full);  // weight 1
    const M active = hn::Or(below, hn::And(hn::Eq(octave, full), hn::Not(hn::Eq(fraction, zero))));
    const M summed = hn::And(active, need);
    if (hn::AllFalse(d, summed)) {
      break;  // the scalar loop has stopped for every needed point
    }
    const V weight = hn::IfThenElse(below, one, fraction);
    h = hn::IfThenElse(
        active, hn::Add(h, hn::Mul(hn::Mul(weight, hn::Set(d, c.amplitude[n])), sample(n))), h);
    octaves += hn::CountTrue(d, summed);
    // The warp moves on after every whole octave but the last (core/fbm.cc).
    if (c.warp && n + 1 < c.count && !hn::AllFalse(d, hn::And(below, need))) {
      warp(below);
    }
  }
  const V height =
      hn::Add(hn::Set(d, c.relative_base_height), hn::Mul(hn::Set(d, c.height_scale), h));
  return hn::IfThenElseZero(need, height);
}

template <Interpolant kKind>
FbmWork FbmRange(const FbmParams<float>& c, const NoiseLattice& lattice, IndexRange range,
                 const float* HWY_RESTRICT dx, const float* HWY_RESTRICT dz,
                 const float* HWY_RESTRICT nu, const std::uint8_t* HWY_RESTRICT mask,
                 float* HWY_RESTRICT height) {
  const hn::ScalableTag<float> d;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  const hn::RebindToSigned<decltype(d)> di;
  const std::size_t lanes = hn::Lanes(d);
  const LatticeView view = view_of(lattice);
  FbmWork work;
  const auto needed = [&](const std::uint8_t* m) {
    if (m == nullptr) {
      return hn::FirstN(d, lanes);  // no mask: every point
    }
    return hn::RebindMask(d, hn::Ne(hn::PromoteTo(di, hn::LoadU(d8, m)), hn::Zero(di)));
  };
  std::size_t k = range.begin;
  for (; k + lanes <= range.end; k += lanes) {
    const auto need = needed(mask == nullptr ? nullptr : mask + k);
    work.points += hn::CountTrue(d, need);
    if (hn::AllFalse(d, need)) {
      hn::StoreU(hn::Zero(d), d, height + k);
      continue;
    }
    hn::StoreU(FbmVector<kKind>(d, c, view, hn::LoadU(d, dx + k), hn::LoadU(d, dz + k),
                                hn::LoadU(d, nu + k), need, work.octaves),
               d, height + k);
  }
  if (k < range.end) {
    // The last points: a full vector whose extra lanes are not needed.
    HWY_ALIGN float tail_dx[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_dz[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_nu[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_height[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t tail_mask[HWY_MAX_BYTES / sizeof(float)] = {};
    const std::size_t count = range.end - k;
    for (std::size_t t = 0; t < count; ++t) {
      tail_dx[t] = dx[k + t];
      tail_dz[t] = dz[k + t];
      tail_nu[t] = nu[k + t];
      tail_mask[t] = mask == nullptr ? 1 : mask[k + t];
    }
    const auto need = needed(tail_mask);
    work.points += hn::CountTrue(d, need);
    hn::Store(FbmVector<kKind>(d, c, view, hn::Load(d, tail_dx), hn::Load(d, tail_dz),
                               hn::Load(d, tail_nu), need, work.octaves),
              d, tail_height);
    for (std::size_t t = 0; t < count; ++t) {
      height[k + t] = tail_height[t];
    }
  }
  return work;
}

FbmWork EvaluateFbm(const FbmParams<float>& c, const NoiseLattice& lattice, IndexRange range,
                    const float* dx, const float* dz, const float* nu, const std::uint8_t* mask,
                    float* height) {
  switch (static_cast<Interpolant>(c.interpolant)) {
    case Interpolant::kLinear:
      return FbmRange<Interpolant::kLinear>(c, lattice, range, dx, dz, nu, mask, height);
    case Interpolant::kCubic:
      return FbmRange<Interpolant::kCubic>(c, lattice, range, dx, dz, nu, mask, height);
    case Interpolant::kQuintic:
      return FbmRange<Interpolant::kQuintic>(c, lattice, range, dx, dz, nu, mask, height);
  }
  return {};
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
