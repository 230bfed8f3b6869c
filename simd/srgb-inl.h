// Per-target body of simd/srgb.h. srgb_byte finds the code in a table by the value's top 16
// bits and steps it up at most once (srgb_detail::bucket_steps); here both lookups are gathers
// and the step a compare, with srgb_byte's answers outside (0, 1): 0 at or below 0 and for
// NaN, 255 from 1 up.
#if defined(RELIEF_SIMD_SRGB_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SRGB_INL_H_
#undef RELIEF_SIMD_SRGB_INL_H_
#else
#define RELIEF_SIMD_SRGB_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/srgb.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> SrgbCodes(D d, V linear,
                                                    const srgb_detail::BucketSteps& steps) {
  const hn::RebindToSigned<D> di;
  const auto inside = hn::And(hn::Gt(linear, hn::Zero(d)), hn::Lt(linear, hn::Set(d, 1.0f)));
  // Bucket of a value in (0, 1): its top 16 bits, below 0x3f80; 0 for the others (not used).
  const auto bucket =
      hn::IfThenElseZero(hn::RebindMask(di, inside), hn::ShiftRight<16>(hn::BitCast(di, linear)));
  const auto first = hn::GatherIndex(di, steps.code.data(), bucket);
  const auto next_at = hn::GatherIndex(d, steps.next_at.data(), bucket);
  const auto stepped = hn::IfThenElse(hn::RebindMask(di, hn::Ge(linear, next_at)),
                                      hn::Add(first, hn::Set(di, 1)), first);
  const auto top = hn::RebindMask(di, hn::Ge(linear, hn::Set(d, 1.0f)));
  return hn::IfThenElse(top, hn::Set(di, 255),
                        hn::IfThenElseZero(hn::RebindMask(di, inside), stepped));
}

void EncodeSrgb(const float* HWY_RESTRICT linear, std::uint8_t* HWY_RESTRICT out,
                std::size_t count) {
  const hn::ScalableTag<float> d;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  const std::size_t lanes = hn::Lanes(d);
  const srgb_detail::BucketSteps& steps = srgb_detail::bucket_steps();
  std::size_t k = 0;
  for (; k + lanes <= count; k += lanes) {
    hn::StoreU(hn::DemoteTo(d8, SrgbCodes(d, hn::LoadU(d, linear + k), steps)), d8, out + k);
  }
  if (k < count) {
    HWY_ALIGN float tail[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t codes[HWY_MAX_BYTES / sizeof(float)] = {};
    for (std::size_t t = 0; t < count - k; ++t) {
      tail[t] = linear[k + t];
    }
    hn::Store(hn::DemoteTo(d8, SrgbCodes(d, hn::Load(d, tail), steps)), d8, codes);
    for (std::size_t t = 0; t < count - k; ++t) {
      out[k + t] = codes[t];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
