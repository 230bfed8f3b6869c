#include "eval/pareto.h"

#include <cstddef>

namespace relief {

bool dominates(const ParetoPoint& a, const ParetoPoint& b) {
  return a.time <= b.time && a.error <= b.error && (a.time < b.time || a.error < b.error);
}

bool dominates_beyond(const ParetoPoint& a, const ParetoPoint& b, double time_tolerance,
                      double error_tolerance) {
  return dominates(a, b) && (b.time - a.time > time_tolerance * b.time ||
                             b.error - a.error > error_tolerance * b.error);
}

// Quadratic in the number of points: a sweep has a few dozen.
std::vector<bool> pareto_front(std::span<const ParetoPoint> points) {
  std::vector<bool> on_front(points.size(), true);
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (std::size_t j = 0; j < points.size() && on_front[k]; ++j) {
      if (j != k && dominates(points[j], points[k])) {
        on_front[k] = false;
      }
    }
  }
  return on_front;
}

}  // namespace relief
