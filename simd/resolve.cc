// Highway's per-target compilation of simd/resolve-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/resolve.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/resolve-inl.h"

#if HWY_ONCE
#include <algorithm>

#include "simd/resolve.h"

namespace relief::simd {

HWY_EXPORT(ResolveRect);
HWY_EXPORT(SetUpPlanes);

void set_up_planes(const float* clip_x, const float* clip_y, const float* clip_w,
                   const WindowTransform& window, const std::int32_t* const vertex[3],
                   std::size_t count, double* const k[3], double* const ku[3],
                   double* const kv[3]) {
  HWY_DYNAMIC_DISPATCH(SetUpPlanes)(clip_x, clip_y, clip_w, window, vertex, count, k, ku, kv);
}

void gather_slot_records(const ResolveStreams& streams, const std::int32_t* const vertex[3],
                         std::size_t count, float* records) {
  const float* const stream[kResolveStreams] = {
      streams.dx,    streams.dz,          streams.height, streams.nx,      streams.ny,  streams.nz,
      streams.slope, streams.water_depth, streams.nu,     streams.lambert, streams.drop};
  // Absent streams and the padding are zero; the present ones are copied slot by slot.
  std::fill(records, records + count * kSlotRecordFloats, 0.0f);
  for (int f = 0; f < kResolveStreams; ++f) {
    const float* const values = stream[f];
    if (values == nullptr) {
      continue;
    }
    for (std::size_t s = 0; s < count; ++s) {
      float* const record = records + s * kSlotRecordFloats + 3 * f;
      record[0] = values[vertex[0][s]];
      record[1] = values[vertex[1][s]];
      record[2] = values[vertex[2][s]];
    }
  }
}

void resolve_rect(const ResolveSlots& slots, const ResolveStreams& streams,
                  const std::int32_t* slot, int x0, int y0, int width, int height, int stride,
                  const ResolveTargets& out) {
  HWY_DYNAMIC_DISPATCH(ResolveRect)(slots, streams, slot, x0, y0, width, height, stride, out);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
