// Highway's per-target compilation of simd/fbm-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/fbm.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/fbm-inl.h"

#if HWY_ONCE
#include "simd/fbm.h"

namespace relief::simd {

HWY_EXPORT(EvaluateFbm);

FbmWork evaluate_fbm(const FbmParams<float>& params, const NoiseLattice& lattice, IndexRange range,
                     std::span<const float> dx, std::span<const float> dz,
                     std::span<const float> nu, std::span<const std::uint8_t> mask,
                     std::span<float> height) {
  return HWY_DYNAMIC_DISPATCH(EvaluateFbm)(params, lattice, range, dx.data(), dz.data(), nu.data(),
                                           mask.empty() ? nullptr : mask.data(), height.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
