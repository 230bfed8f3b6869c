#include "core/screen_grid.h"

#include <algorithm>

#include "core/frustum_polytope.h"

namespace relief {

ScreenGrid make_screen_grid(const GridSettings& grid, const Projector& projector) {
  const ImageBox& box = projector.coverage;
  ScreenGrid screen;
  screen.width = grid.width;
  screen.height = grid.height;
  screen.margin = grid.margin;
  // Divisions by the inner cells' counts (rows here, columns below): >= 1 by the precondition.
  screen.step_y = (box.y1 - box.y0) / (grid.height - 1 - 2 * grid.margin);
  screen.y0 = box.y0 - grid.margin * screen.step_y;
  const double inner_columns = grid.width - 1 - 2 * grid.margin;
  double hull_y0 = box.y0, hull_y1 = box.y1;
  for (const glm::dvec2& p : projector.hull) {
    hull_y0 = std::min(hull_y0, p.y);
    hull_y1 = std::max(hull_y1, p.y);
  }
  const double min_span = kMinRowSpanFraction * (box.x1 - box.x0);
  // Rows -1 .. height at index j + 1: first each row's own span.
  const std::size_t rows = static_cast<std::size_t>(grid.height) + 2;
  std::vector<double> lo(rows), hi(rows);
  for (int j = -1; j <= grid.height; ++j) {
    // The hull's extent between the neighbouring rows (header). The margin rows past the
    // inner ones repeat the span of the last inner row: the hull ends there.
    const int inner = std::clamp(j, grid.margin, grid.height - 1 - grid.margin);
    const double y_lo = std::clamp(screen.image_y(inner - 1), hull_y0, hull_y1);
    const double y_hi = std::clamp(screen.image_y(inner + 1), hull_y0, hull_y1);
    double x_lo = box.x0, x_hi = box.x1;
    if (!hull_span_between(projector.hull, y_lo, y_hi, x_lo, x_hi)) {
      x_lo = box.x0;  // no hull (nothing visible): the box
      x_hi = box.x1;
    }
    if (x_hi - x_lo < min_span) {
      const double centre = 0.5 * (x_lo + x_hi);
      x_lo = centre - 0.5 * min_span;
      x_hi = centre + 0.5 * min_span;
    }
    lo[static_cast<std::size_t>(j + 1)] = x_lo;
    hi[static_cast<std::size_t>(j + 1)] = x_hi;
  }
  // Then the shear limit (kMaxShearColumns), by widening only: the smallest spans whose ends
  // move from row k to k + 1 by at most c_k = kMaxShearColumns x the narrower row's column
  // step before widening. A forward and a backward pass give the lower envelope of the cones
  // lo(k) + sum c over the rows between (a distance transform); the steps only grow, so the
  // shift stays within kMaxShearColumns of the final steps.
  std::vector<double> c(rows - 1);
  for (std::size_t k = 0; k + 1 < rows; ++k) {
    c[k] = kMaxShearColumns * std::min(hi[k] - lo[k], hi[k + 1] - lo[k + 1]) / inner_columns;
  }
  for (std::size_t k = 0; k + 1 < rows; ++k) {
    lo[k + 1] = std::min(lo[k + 1], lo[k] + c[k]);
    hi[k + 1] = std::max(hi[k + 1], hi[k] - c[k]);
  }
  for (std::size_t k = rows - 1; k-- > 0;) {
    lo[k] = std::min(lo[k], lo[k + 1] + c[k]);
    hi[k] = std::max(hi[k], hi[k + 1] - c[k]);
  }
  screen.row_x0.resize(rows);
  screen.row_step_x.resize(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    screen.row_step_x[k] = (hi[k] - lo[k]) / inner_columns;
    screen.row_x0[k] = lo[k] - grid.margin * screen.row_step_x[k];
  }
  return screen;
}

}  // namespace relief
