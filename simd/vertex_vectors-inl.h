// The per-vertex loop of the element-wise Highway kernels (stage 5's transform and light,
// a planet's bend): whole vectors of a range, its tail through copies, and the lanes a flag
// byte marks. Included by a kernel's -inl.h inside its per-target section (Highway's
// re-inclusion guard).
#if defined(RELIEF_SIMD_VERTEX_VECTORS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_VERTEX_VECTORS_INL_H_
#undef RELIEF_SIMD_VERTEX_VECTORS_INL_H_
#else
#define RELIEF_SIMD_VERTEX_VECTORS_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/grid_buffers.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// Runs `body(active, in, out)` on every vector of vertices [range.begin, range.end): `in` the
// N input streams' lanes, `active` the lanes whose flag byte has one of `bits` (stage 5:
// need's kDraw; the bend: any valid byte), every lane where `flags` is null, and stores the M
// vectors `body` leaves in `out` into the M output streams. The last, partial vector reads
// and writes its lanes through copies (its missing lanes inactive): nothing outside the range
// is touched.
template <int N, int M, class Body>
HWY_INLINE void ForEachVertexVector(IndexRange range, const float* const (&inputs)[N],
                                    const std::uint8_t* HWY_RESTRICT flags, std::uint8_t bits,
                                    float* const (&outputs)[M], const Body& body) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const auto flag_bits = hn::Set(di, bits);
  const auto one_vector = [&](std::size_t k, std::size_t count) {
    HWY_ALIGN float in[N][HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t tail_flags[HWY_MAX_BYTES / sizeof(float)] = {};
    const bool whole = count == lanes;
    if (!whole) {
      for (std::size_t l = 0; l < count; ++l) {
        for (int c = 0; c < N; ++c) {
          in[c][l] = inputs[c][k + l];
        }
        tail_flags[l] = flags == nullptr ? bits : flags[k + l];
      }
    }
    V values[N];
    for (int c = 0; c < N; ++c) {
      values[c] = whole ? hn::LoadU(d, inputs[c] + k) : hn::Load(d, in[c]);
    }
    auto drawn = hn::FirstN(d, count);
    if (flags != nullptr || !whole) {
      const auto lane_flags =
          hn::PromoteTo(di, whole ? hn::LoadU(d8, flags + k) : hn::Load(d8, tail_flags));
      drawn = hn::RebindMask(d, hn::Ne(hn::And(lane_flags, flag_bits), hn::Zero(di)));
    }
    V results[M];
    body(drawn, values, results);
    HWY_ALIGN float out[HWY_MAX_BYTES / sizeof(float)];
    for (int c = 0; c < M; ++c) {
      if (whole) {
        hn::StoreU(results[c], d, outputs[c] + k);
      } else {
        hn::Store(results[c], d, out);
        for (std::size_t l = 0; l < count; ++l) {
          outputs[c][k + l] = out[l];
        }
      }
    }
  };
  std::size_t k = range.begin;
  for (; k + lanes <= range.end; k += lanes) {
    one_vector(k, lanes);
  }
  if (k < range.end) {
    one_vector(k, range.end - k);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
