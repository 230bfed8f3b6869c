// Stage 1: the screen grid (§4.1, step 1 "start with a uniform grid in screen space").
//
// Gx x Gy vertices in the projector image (projector.h). Rows are regular in image y: the
// inner Gy - 2m rows span the coverage box's height exactly, and m = grid.margin further rows
// continue past it on each side. Each row is regular in image x over its own span: the
// coverage hull's cross-section at the row's image y (the trapezoid-like image of what can be
// seen, instead of the rectangle around it), with m further columns at the row's spacing on
// each side. So the displaced grid has no holes at the viewport borders, border vertices have
// neighbours for the surface pass, and no column lands where no terrain can be seen.
//
// The grid is one mesh whatever the spans: vertex (i, j) is joined to (i + 1, j) and (i, j + 1)
// as before, and between rows j and j + 1 its cells cover the trapezoid between the two rows'
// spans (the footprints of straight image segments are straight). Row j spans the hull's
// extent over [y_j-1, y_j+1], so for every y between two rows both rows' spans contain the
// hull's cross-section at y, and so does the trapezoid: the inner columns alone cover the
// hull, without counting on the margin. The spans vary continuously with the row (a convex
// polygon's extent over a sliding window, widened to at least kMinRowSpanFraction of the box
// and held constant past the hull's y range), so neighbouring rows place their columns alike,
// and stage 2's spacing sigma (from the real footprints of each vertex's neighbours) still
// measures the mesh. Vertex (i, j) is implicit:
// its image point is (row_x0(j) + i row_step_x(j), y0 + j step_y), j = 0 the bottom row (GL's
// window convention). Everything here is double, once per frame; stage 2 reads the rows'
// values rounded once (stage_params.h, make_domain_rows).
#pragma once

#include <cstddef>
#include <vector>

#include "core/projector.h"
#include "core/scene/scene.h"

namespace relief {

// A row's span is at least this fraction of the coverage box's width, centred on the hull's
// cross-section: where the hull ends in a corner, the rows next to it would otherwise squeeze
// all their columns into a sliver (zero-area cells, to no one's benefit).
inline constexpr double kMinRowSpanFraction = 1.0 / 16.0;
// The ends of neighbouring rows' spans differ by at most this many columns (of the narrower
// row): a cell's top edge is shifted against its bottom edge by at most that, so its two
// triangles stay well shaped (a shift of many columns makes slivers, whose interpolated
// heights swing with the slightest rounding of their vertices).
inline constexpr double kMaxShearColumns = 1.0;

struct ScreenGrid {
  int width = 0;
  int height = 0;
  int margin = 0;
  double y0 = 0, step_y = 0;
  // Rows -1 .. height at index j + 1 (stage 2 reads one row beyond each side).
  std::vector<double> row_x0, row_step_x;

  double image_y(double j) const { return y0 + j * step_y; }
  double row_origin(int j) const { return row_x0[static_cast<std::size_t>(j + 1)]; }
  double row_step(int j) const { return row_step_x[static_cast<std::size_t>(j + 1)]; }
  double image_x(double i, int j) const { return row_origin(j) + i * row_step(j); }
};

// Precondition: width, height >= 2 margin + 2 (validate_scene).
ScreenGrid make_screen_grid(const GridSettings& grid, const Projector& projector);

}  // namespace relief
