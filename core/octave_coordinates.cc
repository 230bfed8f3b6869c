#include "core/octave_coordinates.h"

#include <algorithm>
#include <cmath>

namespace relief {

void OctaveReach::merge(const OctaveReach& other) {
  for (std::size_t n = 0; n < extent.size(); ++n) {
    extent[n] = std::max(extent[n], other.extent[n]);
  }
}

int finest_octave(double nu) {
  if (nu <= 1.0) {
    return 0;
  }
  if (nu < double(limits::kMaxOctaves)) {
    return static_cast<int>(std::ceil(nu)) - 1;
  }
  return limits::kMaxOctaves - 1;
}

OctaveReach running_reach(const OctaveReach& by_finest) {
  OctaveReach reach;
  double farthest = 0.0;
  for (int n = limits::kMaxOctaves - 1; n >= 0; --n) {
    farthest = std::max(farthest, by_finest.extent[n]);
    reach.extent[n] = farthest;
  }
  return reach;
}

template <class Real>
OctaveReach octave_reach(IndexRange range, std::span<const Real> dx, std::span<const Real> dz,
                         std::span<const Real> nu, std::span<const std::uint8_t> valid) {
  // The farthest vertex per finest octave summed (octave ceil(nu) - 1: fbm.h sums octave n
  // where n < nu), then a running maximum from the fine octaves down: a vertex summing octave
  // n sums every coarser one.
  OctaveReach by_finest;
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (!valid[k]) {
      continue;
    }
    const int n = finest_octave(double(nu[k]));
    const double extent = std::max(std::abs(double(dx[k])), std::abs(double(dz[k])));
    by_finest.extent[n] = std::max(by_finest.extent[n], extent);
  }
  return running_reach(by_finest);
}

template <class Real>
void choose_coordinate_forms(const TerrainPlan& plan, const OctaveReach& reach,
                             FbmParams<Real>& params) {
  const double period = static_cast<double>(plan.lattice->size);
  for (int n = 0; n < plan.octaves.count; ++n) {
    params.exact_coordinates[n] = plan.octaves.scale[n] * reach.extent[n] > period ? 1 : 0;
  }
}

template OctaveReach octave_reach<float>(IndexRange, std::span<const float>, std::span<const float>,
                                         std::span<const float>, std::span<const std::uint8_t>);
template OctaveReach octave_reach<double>(IndexRange, std::span<const double>,
                                          std::span<const double>, std::span<const double>,
                                          std::span<const std::uint8_t>);
template void choose_coordinate_forms<float>(const TerrainPlan&, const OctaveReach&,
                                             FbmParams<float>&);
template void choose_coordinate_forms<double>(const TerrainPlan&, const OctaveReach&,
                                              FbmParams<double>&);

}  // namespace relief
