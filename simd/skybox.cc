// Highway's per-target compilation of simd/skybox-inl.h over arrays and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/skybox.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstddef>

#include "simd/skybox-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

void SkyboxRadiances(const Skybox& skybox, const float* x, const float* y, const float* z,
                     std::size_t count, float* HWY_RESTRICT rgb) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  const SkyboxView box = skybox_view_of(&skybox);
  constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float out[3 * kMaxLanes];
  HWY_ALIGN float tail[3][kMaxLanes];
  for (std::size_t k = 0; k < count; k += lanes) {
    const std::size_t n = count - k < lanes ? count - k : lanes;
    // The tail's unused lanes hold zeros: the +x face's centre, discarded.
    const float* from[3] = {x + k, y + k, z + k};
    if (n < lanes) {
      for (int c = 0; c < 3; ++c) {
        for (std::size_t t = 0; t < kMaxLanes; ++t) {
          tail[c][t] = t < n ? from[c][t] : 0.0f;
        }
        from[c] = tail[c];
      }
    }
    const V3<hn::Vec<decltype(d)>> dir{hn::LoadU(d, from[0]), hn::LoadU(d, from[1]),
                                       hn::LoadU(d, from[2])};
    const auto c = SkyboxRadiance(d, box, dir);
    hn::StoreInterleaved3(c.x, c.y, c.z, d, out);
    for (std::size_t t = 0; t < 3 * n; ++t) {
      rgb[3 * k + t] = out[t];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <stdexcept>

#include "simd/skybox.h"

namespace relief::simd {

HWY_EXPORT(SkyboxRadiances);

void skybox_radiances(const Skybox& box, std::span<const float> x, std::span<const float> y,
                      std::span<const float> z, std::span<float> rgb) {
  if (y.size() != x.size() || z.size() != x.size() || rgb.size() != 3 * x.size()) {
    throw std::invalid_argument("skybox_radiances: x, y, z of one length, rgb three times it");
  }
  if (box.size < 1 || box.texels.size() != 18 * std::size_t(box.size) * std::size_t(box.size)) {
    throw std::invalid_argument("skybox_radiances: the box needs six faces of size^2 texels");
  }
  HWY_DYNAMIC_DISPATCH(SkyboxRadiances)(box, x.data(), y.data(), z.data(), x.size(), rgb.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
