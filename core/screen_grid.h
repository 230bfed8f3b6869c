// Stage 1: the screen grid (§4.1, step 1 "start with a uniform grid in screen space").
//
// Gx x Gy vertices on a regular lattice of the projector image (projector.h). The inner
// (Gx - 2m) x (Gy - 2m) vertices span the coverage box exactly; m = grid.margin further rows
// and columns of cells continue the lattice past it on every side, so the displaced grid has
// no holes at the viewport borders and border vertices have neighbours for the surface pass.
// Vertex (i, j) is implicit: its image point is (x0 + i step_x, y0 + j step_y), j = 0 the
// bottom row (GL's window convention).
#pragma once

#include "core/projector.h"
#include "core/scene/scene.h"

namespace relief {

struct ScreenGrid {
  int width = 0;
  int height = 0;
  int margin = 0;
  double x0 = 0, step_x = 0;
  double y0 = 0, step_y = 0;

  double image_x(double i) const { return x0 + i * step_x; }
  double image_y(double j) const { return y0 + j * step_y; }
};

// Precondition: width, height >= 2 margin + 2 (validate_scene).
inline ScreenGrid make_screen_grid(const GridSettings& grid, const ImageBox& coverage) {
  ScreenGrid screen;
  screen.width = grid.width;
  screen.height = grid.height;
  screen.margin = grid.margin;
  screen.step_x = (coverage.x1 - coverage.x0) / (grid.width - 1 - 2 * grid.margin);
  screen.step_y = (coverage.y1 - coverage.y0) / (grid.height - 1 - 2 * grid.margin);
  screen.x0 = coverage.x0 - grid.margin * screen.step_x;
  screen.y0 = coverage.y0 - grid.margin * screen.step_y;
  return screen;
}

}  // namespace relief
