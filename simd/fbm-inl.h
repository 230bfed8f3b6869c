// Per-target body of simd/fbm.h: fbm_point of core/fbm.cc on a vector of points. Lanes whose
// octaves are done (n past their nu) keep their height and warp through masks, so each lane
// computes exactly what the scalar loop computes for its point; the vector stops at the first
// octave no needed lane sums. The lattice is sampled by simd/fbm_lattice-inl.h (windows of
// lattice rows where the points are close together, 64-bit gathers elsewhere).
#if defined(RELIEF_SIMD_FBM_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_FBM_INL_H_
#undef RELIEF_SIMD_FBM_INL_H_
#else
#define RELIEF_SIMD_FBM_INL_H_
#endif

#include <cstddef>
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

// The inputs of one vector of points that every octave reads.
template <class V>
struct FbmPoints {
  V dx, dz;                      // camera-relative position, world units
  V ux, uz;                      // dx, dz in octave-0 cells (the direct form)
  V dx_hi, dx_lo, dz_hi, dz_lo;  // the halves of dx, dz (the exact form)
};

// S at octave n for every lane, W_n = (wx, wz); `shifted`: W_n is added (it is +-0 in every
// lane otherwise, which changes no result: x + -0 is x, and x + +0 differs only for x = -0,
// which samples as +0 does, SampleFbmLattice).
template <Interpolant kKind, class D, class V = hn::Vec<D>>
HWY_INLINE V OctaveSample(D d, const FbmParams<float>& c, const FbmLattice& lattice, int n,
                          const FbmPoints<V>& p, bool shifted, V wx, V wz) {
  V px =
      hn::Add(hn::Set(d, c.offset_x[n]), ScaledCoordinate(d, c, n, p.dx, p.ux, p.dx_hi, p.dx_lo));
  V pz =
      hn::Add(hn::Set(d, c.offset_z[n]), ScaledCoordinate(d, c, n, p.dz, p.uz, p.dz_hi, p.dz_lo));
  if (shifted) {
    px = hn::Add(px, wx);
    pz = hn::Add(pz, wz);
  }
  return SampleFbmLattice<kKind>(d, lattice, px, pz);
}

// §2.2: R_n, rot_{n+1}, t_{n+1} and W_{n+1} after a whole octave (core/fbm.cc), in the lanes
// of `moves`; h = H_n.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void Warp(D d, const FbmParams<float>& c, M moves, V h, V& rx, V& rz, V& wx, V& wz) {
  const V roughness = hn::Sub(hn::Set(d, c.roughness0), h);
  const V inv_roughness =
      hn::Div(roughness, hn::Add(hn::Mul(roughness, roughness), hn::Set(d, c.guard_sq)));
  const V vx = hn::Add(hn::Add(hn::Mul(hn::Set(d, c.c1x), roughness), hn::Set(d, c.c2x)), rx);
  const V vz = hn::Add(hn::Add(hn::Mul(hn::Set(d, c.c1z), roughness), hn::Set(d, c.c2z)), rz);
  const V length_sq = hn::Add(hn::Mul(vx, vx), hn::Mul(vz, vz));
  const M renormalise = hn::And(moves, hn::Gt(length_sq, hn::Set(d, c.min_rotation_sq)));
  const V inv_length = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(length_sq));
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
}

// K vectors of points side by side (independent chains of octaves for the out-of-order core
// to overlap: with the warp, each octave's coordinate waits for the previous octave's height);
// need[k] selects the lanes to evaluate. Stores the heights (0 where not needed) and adds the
// octaves summed by needed lanes to `octaves`. Each vector computes what it computes alone.
template <Interpolant kKind, int K, class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void FbmVectors(D d, const FbmParams<float>& c, const FbmLattice& lattice,
                           const V (&dx)[K], const V (&dz)[K], const V (&nu)[K], const M (&need)[K],
                           V (&height)[K], std::uint64_t& octaves) {
  const V one = hn::Set(d, 1.0f);
  const V zero = hn::Zero(d);
  const V count = hn::Set(d, float(c.count));
  const bool shifted = c.warp || c.t0x != 0.0f || c.t0z != 0.0f;
  const M every_lane = hn::FirstN(d, hn::Lanes(d));
  FbmPoints<V> p[K];
  V full[K], fraction[K];
  V h[K];
  V wx[K], wz[K];  // W_n, §2.2
  V rx[K], rz[K];  // rot_n, §2.2
  std::uint64_t needed_lanes[K];
  int whole_for_all = c.count;  // octaves every needed lane of every vector sums whole
  for (int k = 0; k < K; ++k) {
    p[k].dx = dx[k];
    p[k].dz = dz[k];
    p[k].ux = hn::Mul(dx[k], hn::Set(d, c.inv_scale));
    p[k].uz = hn::Mul(dz[k], hn::Set(d, c.inv_scale));
    SplitHalves(d, dx[k], p[k].dx_hi, p[k].dx_lo);
    SplitHalves(d, dz[k], p[k].dz_hi, p[k].dz_lo);
    // §4.1: floor(nu) whole octaves (at most N), then one weighted by the fraction. Integers
    // below 2^24 compare exactly as floats.
    const V whole = hn::Floor(nu[k]);
    full[k] = hn::IfThenElse(hn::Lt(whole, count), whole, count);
    fraction[k] = hn::Sub(nu[k], whole);
    h[k] = zero;
    wx[k] = hn::Set(d, c.t0x);
    wz[k] = hn::Set(d, c.t0z);
    rx[k] = hn::Set(d, c.r0x);
    rz[k] = hn::Set(d, c.r0z);
    const float fewest_full =
        hn::GetLane(hn::MinOfLanes(d, hn::IfThenElse(need[k], full[k], count)));
    const int whole_here = fewest_full > 0.0f ? static_cast<int>(fewest_full) : 0;
    whole_for_all = whole_here < whole_for_all ? whole_here : whole_for_all;
    needed_lanes[k] = hn::CountTrue(d, need[k]);
  }
  // First the octaves every needed lane sums whole, without masks: weight 1, and (1 a_n) S is
  // a_n S exactly.
  int n = 0;
  for (; n < whole_for_all; ++n) {
    for (int k = 0; k < K; ++k) {
      const V s = OctaveSample<kKind>(d, c, lattice, n, p[k], shifted, wx[k], wz[k]);
      h[k] = hn::Add(h[k], hn::Mul(hn::Set(d, c.amplitude[n]), s));
      octaves += needed_lanes[k];
      if (c.warp && n + 1 < c.count) {
        Warp(d, c, every_lane, h[k], rx[k], rz[k], wx[k], wz[k]);
      }
    }
  }
  // Then lane by lane: the fractional octave, and lanes whose nu ends earlier. A vector is done
  // at the first octave none of its needed lanes sums (the scalar loop has stopped for each of
  // them: no later octave is summed either).
  bool done[K] = {};
  for (; n < c.count; ++n) {
    bool any = false;
    for (int k = 0; k < K; ++k) {
      if (done[k]) {
        continue;
      }
      const V octave = hn::Set(d, float(n));
      const M below = hn::Lt(octave, full[k]);  // weight 1
      const M active =
          hn::Or(below, hn::And(hn::Eq(octave, full[k]), hn::Not(hn::Eq(fraction[k], zero))));
      const M summed = hn::And(active, need[k]);
      if (hn::AllFalse(d, summed)) {
        done[k] = true;
        continue;
      }
      any = true;
      const V weight = hn::IfThenElse(below, one, fraction[k]);
      const V s = OctaveSample<kKind>(d, c, lattice, n, p[k], shifted, wx[k], wz[k]);
      h[k] = hn::IfThenElse(
          active, hn::Add(h[k], hn::Mul(hn::Mul(weight, hn::Set(d, c.amplitude[n])), s)), h[k]);
      octaves += hn::CountTrue(d, summed);
      // The warp moves on after every whole octave but the last (core/fbm.cc).
      if (c.warp && n + 1 < c.count && !hn::AllFalse(d, hn::And(below, need[k]))) {
        Warp(d, c, below, h[k], rx[k], rz[k], wx[k], wz[k]);
      }
    }
    if (!any) {
      break;
    }
  }
  for (int k = 0; k < K; ++k) {
    height[k] = hn::IfThenElseZero(need[k], hn::Add(hn::Set(d, c.relative_base_height),
                                                    hn::Mul(hn::Set(d, c.height_scale), h[k])));
  }
}

// The mask of the needed lanes of the vector at m (every lane where there is no mask).
template <class D>
HWY_INLINE hn::Mask<D> NeededLanes(D d, const std::uint8_t* m) {
  if (m == nullptr) {
    return hn::FirstN(d, hn::Lanes(d));
  }
  const hn::Rebind<std::uint8_t, D> d8;
  const hn::RebindToSigned<D> di;
  return hn::RebindMask(d, hn::Ne(hn::PromoteTo(di, hn::LoadU(d8, m)), hn::Zero(di)));
}

// K full vectors of points from point k on.
template <Interpolant kKind, int K, class D>
HWY_INLINE void FbmRun(D d, const FbmParams<float>& c, const FbmLattice& lattice,
                       const float* HWY_RESTRICT dx, const float* HWY_RESTRICT dz,
                       const float* HWY_RESTRICT nu, const std::uint8_t* HWY_RESTRICT mask,
                       float* HWY_RESTRICT height, std::size_t k, FbmWork& work) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const std::size_t lanes = hn::Lanes(d);
  V vx[K], vz[K], vnu[K], out[K];
  M need[K];
  bool any = false;
  for (int v = 0; v < K; ++v) {
    const std::size_t at = k + static_cast<std::size_t>(v) * lanes;
    need[v] = NeededLanes(d, mask == nullptr ? nullptr : mask + at);
    work.points += hn::CountTrue(d, need[v]);
    any = any || !hn::AllFalse(d, need[v]);
    vx[v] = hn::LoadU(d, dx + at);
    vz[v] = hn::LoadU(d, dz + at);
    vnu[v] = hn::LoadU(d, nu + at);
    out[v] = hn::Zero(d);
  }
  if (any) {
    FbmVectors<kKind, K>(d, c, lattice, vx, vz, vnu, need, out, work.octaves);
  }
  for (int v = 0; v < K; ++v) {
    hn::StoreU(out[v], d, height + k + static_cast<std::size_t>(v) * lanes);
  }
}

template <Interpolant kKind>
FbmWork FbmRange(const FbmParams<float>& c, const NoiseLattice& lattice, IndexRange range,
                 const float* HWY_RESTRICT dx, const float* HWY_RESTRICT dz,
                 const float* HWY_RESTRICT nu, const std::uint8_t* HWY_RESTRICT mask,
                 float* HWY_RESTRICT height) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  using M = hn::Mask<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const FbmLattice view = FbmLatticeOf(d, lattice);
  FbmWork work;
  std::size_t k = range.begin;
  if (c.warp) {
    // Three vectors side by side: each octave's coordinate waits for the warp of the previous
    // octave (a division and a square root after the sample). Without the warp the octaves of
    // one vector are independent already, and more vectors only add register pressure.
    for (; k + 3 * lanes <= range.end; k += 3 * lanes) {
      FbmRun<kKind, 3>(d, c, view, dx, dz, nu, mask, height, k, work);
    }
  }
  for (; k + lanes <= range.end; k += lanes) {
    FbmRun<kKind, 1>(d, c, view, dx, dz, nu, mask, height, k, work);
  }
  if (k < range.end) {
    // The last points: a full vector whose extra lanes are not needed (copies of the last
    // point, so that they do not keep the vector from its windows).
    HWY_ALIGN float tail_dx[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_dz[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_nu[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float tail_height[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t tail_mask[HWY_MAX_BYTES / sizeof(float)] = {};
    const std::size_t count = range.end - k;
    for (std::size_t t = 0; t < lanes; ++t) {
      const std::size_t from = k + (t < count ? t : count - 1);
      tail_dx[t] = dx[from];
      tail_dz[t] = dz[from];
      tail_nu[t] = nu[from];
      tail_mask[t] = t >= count ? 0 : mask == nullptr ? 1 : mask[from];
    }
    const M need[1] = {NeededLanes(d, tail_mask)};
    work.points += hn::CountTrue(d, need[0]);
    const V vx[1] = {hn::Load(d, tail_dx)}, vz[1] = {hn::Load(d, tail_dz)},
            vnu[1] = {hn::Load(d, tail_nu)};
    V out[1];
    FbmVectors<kKind, 1>(d, c, view, vx, vz, vnu, need, out, work.octaves);
    hn::Store(out[0], d, tail_height);
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
