// Highway's per-target compilation of simd/planet_bend-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/planet_bend.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/planet_bend-inl.h"

#if HWY_ONCE
#include "simd/planet_bend.h"

namespace relief::simd {

HWY_EXPORT(BendVertices);
HWY_EXPORT(BendNormals);

void bend_vertices(const PlanetParams<float>& planet, IndexRange range, std::span<const float> dx,
                   std::span<const float> dz, std::span<const float> height,
                   std::span<const std::uint8_t> valid, BentSpans<float> out) {
  HWY_DYNAMIC_DISPATCH(BendVertices)
  (planet, range, dx.data(), dz.data(), height.data(), valid.data(), out.x.data(), out.y.data(),
   out.z.data(), out.drop.data());
}

void bend_normals(const PlanetParams<float>& planet, IndexRange range, std::span<const float> dx,
                  std::span<const float> dz, std::span<const std::uint8_t> valid,
                  std::span<float> nx, std::span<float> ny, std::span<float> nz) {
  HWY_DYNAMIC_DISPATCH(BendNormals)
  (planet, range, dx.data(), dz.data(), valid.data(), nx.data(), ny.data(), nz.data());
}

}  // namespace relief::simd
#endif  // HWY_ONCE
