// mesh_drawn_extent (core/sun_horizons.h): where a GeoMipMap mesh's pixels can lie in the
// sun's frame, for the horizon cache's level range.
#include <algorithm>
#include <cmath>

#include "core/sun_horizons.h"

namespace relief {

template <class Real>
DrawnExtent mesh_drawn_extent(const ShadowPlan& plan, std::span<const std::uint32_t> indices,
                              std::size_t first, std::size_t end, std::span<const Real> dx,
                              std::span<const Real> dz, std::span<const Real> height) {
  DrawnExtent drawn;
  for (std::size_t t = first; t < end; ++t) {
    double u[3], v[3], own[3];
    double low = HUGE_VAL;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t k = indices[3 * t + std::size_t(i)];
      u[i] = double(dx[k]) * plan.axis_x + double(dz[k]) * plan.axis_z;
      v[i] = double(dz[k]) * plan.axis_x - double(dx[k]) * plan.axis_z;
      own[i] = std::max(std::abs(u[i]), std::abs(v[i]));
      low = std::min(low, double(height[k]));
    }
    double edge = 0.0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      edge = std::max({edge, std::abs(u[j] - u[i]), std::abs(v[j] - v[i])});
    }
    const double nearest = std::min({own[0], own[1], own[2]});
    const double farthest = std::max({own[0], own[1], own[2]});
    drawn.nearest = std::min(drawn.nearest, nearest - edge - 1e-4 * nearest);
    // One edge more, as drawn_extent allows: a pixel's barycentrics come from the unsnapped
    // vertices, so a covered pixel may lie a little outside its triangle.
    drawn.farthest = std::max(drawn.farthest, (farthest + edge) * (1.0 + 1e-4));
    drawn.lowest = std::min(drawn.lowest, low);
  }
  return drawn;
}

template DrawnExtent mesh_drawn_extent<float>(const ShadowPlan&, std::span<const std::uint32_t>,
                                              std::size_t, std::size_t, std::span<const float>,
                                              std::span<const float>, std::span<const float>);
template DrawnExtent mesh_drawn_extent<double>(const ShadowPlan&, std::span<const std::uint32_t>,
                                               std::size_t, std::size_t, std::span<const double>,
                                               std::span<const double>, std::span<const double>);

}  // namespace relief
