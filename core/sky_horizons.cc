#include "core/sky_horizons.h"

#include <vector>

#include "core/horizon_lines.h"

namespace relief {

template <class Real>
HorizonWork sweep_sky_columns(const ShadowParams<Real>& p, int level, RowRange columns,
                              SunHorizonCache<Real>& cache) {
  HorizonWork work;
  thread_local std::vector<HullPoint<Real>> hull;
  for (int column = columns.begin; column < columns.end; ++column) {
    sweep_horizon_line(
        p, cache, level, column, SweepDirection{true, 1}, p.sky_reach, hull, work,
        [&](std::size_t k, Real along, Real h, const HullPoint<Real>* ahead, const auto& plane) {
          cache.sky[k] = cache.sky[k] + sky_openness(horizon_tangent(along, h, ahead), plane());
        });
    // The fourth direction, then the mean of the four (summed in one order: the same bits
    // whichever thread swept which line).
    sweep_horizon_line(
        p, cache, level, column, SweepDirection{true, -1}, p.sky_reach, hull, work,
        [&](std::size_t k, Real along, Real h, const HullPoint<Real>* ahead, const auto& plane) {
          cache.sky[k] =
              (cache.sky[k] + sky_openness(horizon_tangent(along, h, ahead), plane())) * Real(0.25);
        });
  }
  return work;
}

template <class Real>
Real sky_visibility(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c, Real dx, Real dz,
                    SkyWork& work) {
  ++work.pixels;
  const Real u = dx * p.axis_x + dz * p.axis_z;
  const Real v = dz * p.axis_x - dx * p.axis_z;
  // Bilinear between the four samples around the point: exactly 1 where all four are.
  const auto at = [&](int level, Real fi, Real fj) {
    const int i = int(fi), j = int(fj);  // floor: both >= 0
    const Real f = fi - Real(i), g = fj - Real(j);
    const Real* s = c.sky.data();
    const Real low =
        s[c.index(level, j, i)] + (s[c.index(level, j, i + 1)] - s[c.index(level, j, i)]) * f;
    const Real high = s[c.index(level, j + 1, i)] +
                      (s[c.index(level, j + 1, i + 1)] - s[c.index(level, j + 1, i)]) * f;
    return low + (high - low) * g;
  };
  Real open = 1;
  if (!blended_level_value(p, u, v, at, open)) {
    ++work.outside;
    return Real(1);
  }
  work.open += open == Real(1);
  return open;
}

template HorizonWork sweep_sky_columns<float>(const ShadowParams<float>&, int, RowRange,
                                              SunHorizonCache<float>&);
template HorizonWork sweep_sky_columns<double>(const ShadowParams<double>&, int, RowRange,
                                               SunHorizonCache<double>&);
template float sky_visibility<float>(const ShadowParams<float>&, const SunHorizonCache<float>&,
                                     float, float, SkyWork&);
template double sky_visibility<double>(const ShadowParams<double>&, const SunHorizonCache<double>&,
                                       double, double, SkyWork&);

}  // namespace relief
