// Highway's per-target compilation of simd/surface-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/surface.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/surface-inl.h"

#if HWY_ONCE
#include "simd/surface.h"

namespace relief::simd {

HWY_EXPORT(SurfaceRows);

void surface_pass(const SurfaceParams<float>& params, RowRange rows, SurfaceInputs<float> in,
                  SurfaceSpans<float> out) {
  HWY_DYNAMIC_DISPATCH(SurfaceRows)(params, rows, in, out);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
