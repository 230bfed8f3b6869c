// Per-target helpers of the horizon cache's per-pixel kernels (simd/sun_share.h,
// simd/sky_share.h): blended_level_value's level search and blend band (core/sun_horizons.h)
// with one pixel per lane, its loop and branches as masks.
#if defined(RELIEF_SIMD_CACHE_LEVEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_CACHE_LEVEL_INL_H_
#undef RELIEF_SIMD_CACHE_LEVEL_INL_H_
#else
#define RELIEF_SIMD_CACHE_LEVEL_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/sun_horizons.h"
#include "simd/shade_vec3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// The finest level from first_level whose square holds each lane's (u, v) (the sun's frame),
// for the lanes of `covered`: returns the lanes found, with their level and sample
// coordinates (fi, fj) there; the others keep level end_level.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE M FindCacheLevel(D d, const ShadowParams<float>& p, V u, V v, M covered, VI& level,
                            V& fi, V& fj) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d);
  const V last = hn::Set(d, float(p.resolution - 1));
  M found = hn::FirstN(d, 0);
  fi = zero;
  fj = zero;
  level = hn::Set(di, p.end_level);
  for (int l = p.first_level; l < p.end_level; ++l) {
    if (hn::AllTrue(d, hn::Or(found, hn::Not(covered)))) {
      break;
    }
    const V a = hn::Mul(hn::Sub(u, hn::Set(d, p.origin_u[l])), hn::Set(d, p.inv_spacing[l]));
    const V b = hn::Mul(hn::Sub(v, hn::Set(d, p.origin_v[l])), hn::Set(d, p.inv_spacing[l]));
    const M in = hn::And(hn::And(hn::Ge(a, zero), hn::Lt(a, last)),
                         hn::And(hn::Ge(b, zero), hn::Lt(b, last)));
    const M fresh = hn::AndNot(found, in);
    fi = hn::IfThenElse(fresh, a, fi);
    fj = hn::IfThenElse(fresh, b, fj);
    level = hn::IfThenElse(hn::RebindMask(di, fresh), hn::Set(di, l), level);
    found = hn::Or(found, in);
  }
  return found;
}

// The lanes of `covered` located in the cache: their (dx, dz) (zeroed in the other lanes) in
// the sun's frame, (u, v), and the finest level holding each (FindCacheLevel). Returns the
// covered lanes found; adds the covered lanes beyond the cache to `outside`.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE M LocateInCache(D d, const ShadowParams<float>& p, V dx, V dz, M covered, V& u, V& v,
                           VI& level, V& fi, V& fj, std::uint64_t& outside) {
  dx = hn::IfThenElseZero(covered, dx);
  dz = hn::IfThenElseZero(covered, dz);
  const V ax = hn::Set(d, p.axis_x), az = hn::Set(d, p.axis_z);
  u = hn::Add(hn::Mul(dx, ax), hn::Mul(dz, az));
  v = hn::Sub(hn::Mul(dz, ax), hn::Mul(dx, az));
  const M found = FindCacheLevel(d, p, u, v, covered, level, fi, fj);
  outside += hn::CountTrue(d, hn::AndNot(found, covered));
  return hn::And(found, covered);
}

// The blend band: the lanes of `active` within blend_samples of their level's edge whose next
// coarser level is built and holds the point, with that level (`entry`), the point's sample
// coordinates there (a, b) and the edge distance (`edge`, for the fade). None: no lane.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE M CoarserBand(D d, const ShadowParams<float>& p, V u, V v, VI level, V fi, V fj,
                         M active, VI& entry, V& a, V& b, V& edge) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d);
  const V last = hn::Set(d, float(p.resolution - 1));
  edge = StdMin(StdMin(fi, fj), StdMin(hn::Sub(last, fi), hn::Sub(last, fj)));
  const VI next = hn::Add(level, hn::Set(di, 1));
  M band = hn::And(active, hn::And(hn::Lt(edge, hn::Set(d, p.blend_samples)),
                                   hn::RebindMask(d, hn::Lt(next, hn::Set(di, p.end_level)))));
  entry = level;
  a = zero;
  b = zero;
  if (hn::AllFalse(d, band)) {
    return band;
  }
  // Levels past the last one built read entry end_level - 1 (their lanes are not in band).
  entry =
      hn::IfThenElse(hn::Lt(next, hn::Set(di, p.end_level)), next, hn::Set(di, p.end_level - 1));
  const V inv = hn::GatherIndex(d, p.inv_spacing, entry);
  a = hn::Mul(hn::Sub(u, hn::GatherIndex(d, p.origin_u, entry)), inv);
  b = hn::Mul(hn::Sub(v, hn::GatherIndex(d, p.origin_v, entry)), inv);
  return hn::And(band, hn::And(hn::And(hn::Ge(a, zero), hn::Lt(a, last)),
                               hn::And(hn::Ge(b, zero), hn::Lt(b, last))));
}

// The index of sample (i, j) = (int fi, int fj) of each lane's level in the cache, and the
// fractions f, g; lanes not `active` index sample 0.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>,
          class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE VI CacheSampleIndex(D d, const SunHorizonCache<float>& c, VI level, V fi, V fj, M active,
                               V& f, V& g) {
  const hn::RebindToSigned<D> di;
  const VI i = hn::ConvertTo(di, fi);  // truncation: both >= 0
  const VI j = hn::ConvertTo(di, fj);
  f = hn::Sub(fi, hn::ConvertTo(d, i));
  g = hn::Sub(fj, hn::ConvertTo(d, j));
  const VI n = hn::Set(di, c.resolution);
  const VI at =
      hn::Add(hn::Mul(hn::Add(hn::Mul(hn::Sub(level, hn::Set(di, c.first_level)), n), j), n), i);
  return hn::IfThenElseZero(hn::RebindMask(di, active), at);
}

// Over a rectangle of pixels, pixel (i, j) at k = j * stride + i: for each vector of a row's
// pixels, the mask of the covered ones (covered[k] != 0xffffffff) and a pointer to that vector
// in each of the `kStreams` input arrays, `body(mask, pointers)` for the vectors whose mask has
// a lane (it loads them whole), its result stored at the covered pixels alone. The last pixels of a
// row are copies, the lanes past it uncovered and zero; no pixel past the row is read or written.
template <int kStreams, class D, class Body>
HWY_INLINE void ForEachCoveredVector(D d, const std::uint32_t* HWY_RESTRICT covered,
                                     const float* const (&streams)[kStreams], int width,
                                     int height_px, int stride, float* HWY_RESTRICT out,
                                     Body&& body) {
  using V = hn::Vec<D>;
  const hn::RebindToUnsigned<D> du;
  const int lanes = static_cast<int>(hn::Lanes(d));
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float tail[kStreams + 1][kMaxLanes] = {};
  HWY_ALIGN std::uint32_t tail_covered[kMaxLanes] = {};
  for (int j = 0; j < height_px; ++j) {
    for (int i = 0; i < width; i += lanes) {
      const std::size_t k = static_cast<std::size_t>(j) * stride + i;
      const int count = width - i < lanes ? width - i : lanes;
      const float* in[kStreams];
      for (int s = 0; s < kStreams; ++s) {
        in[s] = streams[s] + k;
      }
      const std::uint32_t* primitive = covered + k;
      if (count < lanes) {  // the last pixels of the row: copies, the other lanes uncovered
        for (int t = 0; t < lanes; ++t) {
          const bool inside = t < count;
          tail_covered[t] = inside ? covered[k + t] : 0xffffffffu;
          for (int s = 0; s < kStreams; ++s) {
            tail[s][t] = inside ? streams[s][k + t] : 0.0f;
          }
        }
        for (int s = 0; s < kStreams; ++s) {
          in[s] = tail[s];
        }
        primitive = tail_covered;
      }
      const auto m =
          hn::Not(hn::RebindMask(d, hn::Eq(hn::LoadU(du, primitive), hn::Set(du, 0xffffffffu))));
      if (hn::AllFalse(d, m)) {
        continue;
      }
      const V result = body(m, static_cast<const float* const*>(in));
      if (count == lanes) {
        hn::BlendedStore(result, m, d, out + k);
      } else {
        hn::StoreU(result, d, tail[kStreams]);
        for (int t = 0; t < count; ++t) {
          if (covered[k + t] != 0xffffffffu) {
            out[k + t] = tail[kStreams][t];
          }
        }
      }
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
