// Highway's per-target compilation of simd/sky_share-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/sky_share.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/sky_share-inl.h"

#if HWY_ONCE
#include "simd/sky_share.h"

namespace relief::simd {

HWY_EXPORT(SkyShares);

void sky_shares(const ShadowParams<float>& p, const SunHorizonCache<float>& c,
                std::span<const std::uint32_t> covered, std::span<const float> dx,
                std::span<const float> dz, int width, int height_px, int stride,
                std::span<float> share, SkyWork& work) {
  if (width <= 0 || height_px <= 0) {
    return;
  }
  HWY_DYNAMIC_DISPATCH(SkyShares)
  (p, c, covered.data(), dx.data(), dz.data(), width, height_px, stride, share.data(), work);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
