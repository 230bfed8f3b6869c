// The Pareto front of points that minimise two figures (relief sweep: frame time and error).
#pragma once

#include <span>
#include <vector>

namespace relief {

struct ParetoPoint {
  double time = 0;
  double error = 0;
};

// a dominates b: a is no worse in both figures and strictly better in one.
bool dominates(const ParetoPoint& a, const ParetoPoint& b);

// a dominates b by more than the measurement can resolve: a dominates b, and it is better by
// more than `time_tolerance` of b's time or by more than `error_tolerance` of b's error
// (relative tolerances, >= 0). Frame times repeat to a few per cent on a shared machine, so a
// point dominated by less is on the front as far as the measurement can tell.
bool dominates_beyond(const ParetoPoint& a, const ParetoPoint& b, double time_tolerance,
                      double error_tolerance);

// on_front[k]: no point dominates point k. Equal points dominate neither other, so all copies
// of a point on the front are on it. Precondition: every figure is finite (a NaN compares
// false and would sit on the front undominated).
std::vector<bool> pareto_front(std::span<const ParetoPoint> points);

}  // namespace relief
