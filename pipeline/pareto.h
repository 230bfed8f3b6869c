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

// on_front[k]: no point dominates point k. Equal points dominate neither other, so all copies
// of a point on the front are on it. Precondition: every figure is finite (a NaN compares
// false and would sit on the front undominated).
std::vector<bool> pareto_front(std::span<const ParetoPoint> points);

}  // namespace relief
