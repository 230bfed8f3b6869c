// One line of the horizon cache swept toward one direction (sun_horizons.h): the upper convex
// hull of the samples ahead of each sample, kept from the line's far end (each sample pushed
// once, popped at most once), gives every sample of the line its horizon in time linear in
// the line's length. Cast shadows sweep the rows toward the sun; sky light (sky_horizons.h)
// sweeps the rows and the columns toward both of their ends.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sun_horizons.h"

namespace relief {

// A hull point: its position along the sweep and its height.
template <class Real>
struct HullPoint {
  Real along, h;
};

// The horizon of a sample with no terrain ahead of it within the sweep: far below any sun.
inline constexpr double kNoHorizonTangent = -1e6;

// The slope of the horizon that hull point `ahead` sets for the sample at (along, h):
// kNoHorizonTangent without one. The run is positive: every point ahead lies farther along
// the sweep (at least about a spacing).
template <class Real>
Real horizon_tangent(Real along, Real h, const HullPoint<Real>* ahead) {
  if (ahead == nullptr) {
    return Real(kNoHorizonTangent);
  }
  return (ahead->h - h) * (Real(1) / (ahead->along - along));
}

// The direction a sweep looks toward: along a level's rows (u, the sun's horizontal
// direction) or its columns (v), toward increasing (+1) or decreasing (-1) coordinates.
struct SweepDirection {
  bool along_v = false;
  int sign = 1;
};

// Drops the hull points that the new point (along, h) hides (each at most once over a sweep)
// and returns the stack's top: the point that sets the new point's horizon, or null when none
// lies ahead. The hull is upper-convex from the line's far end; the point nearest the new one
// is on top. For the new point, the nearest point of the upper hull of itself and the stack,
// the largest slope to any point ahead is the slope to its hull neighbour.
template <class Real>
const HullPoint<Real>* hull_neighbour(std::vector<HullPoint<Real>>& hull, Real along, Real h,
                                      std::uint64_t& popped) {
  while (hull.size() >= 2) {
    const HullPoint<Real>& a = hull[hull.size() - 1];
    const HullPoint<Real>& b = hull[hull.size() - 2];
    // slope(p, a) <= slope(p, b), both runs positive (b lies beyond a, a beyond p).
    if ((a.h - h) * (b.along - along) > (b.h - h) * (a.along - along)) {
      break;
    }
    hull.pop_back();
    ++popped;
  }
  return hull.empty() ? nullptr : &hull.back();
}

// Sweeps line `line` of level `level` (a row where the direction is along u, a column where
// it is along v) from its far end in `direction`: first the coarser levels' samples past this
// level's far end, up to `reach` beyond it (each level's samples beyond the previous level's
// last, its height interpolated between the two lines around this line's position: the levels
// nest, so the position lies inside every coarser level), then the level's own samples, for
// each of which `visit(index, along, height, ahead, plane)` is called with the hull point that
// sets its horizon (null: none ahead) and `plane`, a callable giving the slope of the level's
// surface there toward the direction (the central difference of its neighbours on the line,
// one-sided at the line's ends; computed only where called). `along` is the position times the
// direction's sign, so that the sweep always runs toward decreasing `along`.
template <class Real, class Visit>
void sweep_horizon_line(const ShadowParams<Real>& p, const SunHorizonCache<Real>& cache, int level,
                        int line, SweepDirection direction, Real reach,
                        std::vector<HullPoint<Real>>& hull, HorizonWork& work, Visit&& visit) {
  const int n = p.resolution;
  const Real* origin_along = direction.along_v ? p.origin_v : p.origin_u;
  const Real* origin_across = direction.along_v ? p.origin_u : p.origin_v;
  const bool forward = direction.sign > 0;
  const auto index = [&](int m, int across, int at) {
    return direction.along_v ? cache.index(m, at, across) : cache.index(m, across, at);
  };
  // Sample `at` of a line of level m: its position along the sweep.
  const auto along = [&](int m, int at) {
    const Real position = origin_along[m] + Real(at) * p.spacing[m];
    return forward ? position : -position;
  };
  // The line's far end: the first sample the sweep visits.
  const auto far_end = [&](int m) { return along(m, forward ? n - 1 : 0); };
  const auto sample = [&](int step) { return forward ? n - 1 - step : step; };

  hull.clear();
  const Real across = origin_across[level] + Real(line) * p.spacing[level];
  const Real last = far_end(level);
  const Real farthest = last + reach;
  int top = level;
  Real covered = last;
  while (top + 1 < p.end_level && covered < farthest) {
    ++top;
    covered = far_end(top);
  }
  for (int m = top; m > level; --m) {
    const Real s = p.spacing[m];
    const Real end_before = far_end(m - 1);
    const Real fj = (across - origin_across[m]) * p.inv_spacing[m];
    const int j0 = std::clamp(int(std::floor(fj)), 0, n - 2);
    const Real g = std::clamp(fj - Real(j0), Real(0), Real(1));
    for (int step = 0; step < n; ++step) {
      const int at = sample(step);
      const Real a = along(m, at);
      if (a <= end_before) {
        break;
      }
      if (m == top && a > farthest + s) {
        continue;  // past the reach (one sample beyond it is kept)
      }
      const Real h0 = cache.height[index(m, j0, at)];
      const Real h1 = cache.height[index(m, j0 + 1, at)];
      const Real h = h0 + (h1 - h0) * g;
      hull_neighbour(hull, a, h, work.popped);
      hull.push_back({a, h});
      ++work.continuation;
    }
  }
  const int toward = forward ? 1 : -1;
  const Real half_inv_spacing = Real(0.5) * p.inv_spacing[level];
  for (int step = 0; step < n; ++step) {
    const int at = sample(step);
    const std::size_t k = index(level, line, at);
    const Real a = along(level, at);
    const Real h = cache.height[k];
    const HullPoint<Real>* ahead = hull_neighbour(hull, a, h, work.popped);
    // The surface's slope toward the direction: N >= 128, so one neighbour at least exists;
    // the run is two spacings, or one at the line's ends.
    const auto plane = [&] {
      const int next = at + toward, previous = at - toward;
      const bool has_next = next >= 0 && next < n, has_previous = previous >= 0 && previous < n;
      const Real h_next = has_next ? cache.height[index(level, line, next)] : h;
      const Real h_previous = has_previous ? cache.height[index(level, line, previous)] : h;
      const Real inv_run = has_next && has_previous ? half_inv_spacing : p.inv_spacing[level];
      return (h_next - h_previous) * inv_run;
    };
    visit(k, a, h, ahead, plane);
    hull.push_back({a, h});
    ++work.samples;
  }
}

}  // namespace relief
