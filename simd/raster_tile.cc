// Highway's per-target compilation of simd/raster_tile-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/raster_tile.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/raster_tile-inl.h"

#if HWY_ONCE
#include "simd/raster_tile.h"

namespace relief::simd {

HWY_EXPORT(DrawTriangles);

void draw_triangles(const EdgeTriangle* triangles, std::size_t count, DepthCompare test,
                    const TileBuffers& tile) {
  HWY_DYNAMIC_DISPATCH(DrawTriangles)(triangles, count, test, tile);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
