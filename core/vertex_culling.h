// Which grid vertices a frame needs (between stages 2 and 3, refined after 3): the projected
// grid covers every base-domain point that could be seen (§4.1, Figure 5), but a vertex off
// screen is part of no triangle that can reach a pixel, and its fBm, normal and transform are
// wasted.
//
// Each valid vertex gets an outcode: bit p set when the vertical segment of every height the
// terrain can have there (the height bounds, camera-relative) lies outside frustum plane p
// (left, right, bottom, top, near; the far plane is at infinity). A triangle is certainly
// invisible when its three vertices share an outside plane; the rasteriser would reject it.
// Once stage 3 has run, the outcodes of the vertices' own heights refine kDraw
// (refine_draw_needs): the rows nearest the camera, kept by the projector because terrain as
// high as the bounds allow could be seen there, mostly lie below the screen. Then
//   kDraw     the vertex belongs to a triangle that may be visible: it needs its height, its
//             normal and its clip position, and its triangles are drawn;
//   kEvaluate kDraw, or a 4-neighbour of a kDraw vertex: it needs its height (the normals of
//             its neighbours read it, core/surface.h).
// A triangle is drawn only if its three vertices are kDraw; the others are certainly
// invisible, and every value a drawn triangle or a kDraw normal reads is computed, so the image
// is the same as with no culling at all (tests/pipeline/skip_test.cc).
#pragma once

#include <cstdint>
#include <span>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"

namespace relief {

enum VertexNeed : std::uint8_t {
  kEvaluate = 1,  // compute the height (stage 3)
  kDraw = 2,      // compute the normal (stage 4) and the clip position (stage 5); draw
};

// The frustum's planes in camera-relative coordinates, inward normals, and the height range of
// the terrain relative to the camera: what the outcodes read, rounded once.
template <class Real>
struct CullParams {
  Real plane[5][3] = {};  // left, right, bottom, top: through the camera; near: offset below
  Real near = 0;          // plane 4: dot(plane[4], p) - near >= 0 inside
  Real height_lo = 0;     // camera-relative bounds of the terrain's height
  Real height_hi = 0;
  Real tolerance = 0;  // relative: outside only below -tolerance |p|, against float rounding
  std::int32_t width = 0, height = 0, pitch = 0;
};

template <class Real>
CullParams<Real> make_cull_params(const FramePlan& plan);

// Outcodes of rows [rows.begin, rows.end) (invalid vertices get 0x1f: they are in no drawn
// triangle anyway). `height` empty: of the segment of the height bounds (before stage 3);
// else of the point at the vertex's own camera-relative height (after it).
template <class Real>
void vertex_outcodes(const CullParams<Real>& params, RowRange rows, std::span<const Real> dx,
                     std::span<const Real> dz, std::span<const Real> height,
                     std::span<const std::uint8_t> valid, std::span<std::uint8_t> outcode);

// How many vertices of some rows got each flag.
struct NeedCount {
  std::uint64_t evaluate = 0;
  std::uint64_t draw = 0;
  std::uint64_t valid_draw = 0;  // flagged kDraw and valid: the normals stage 4 computes
};

// VertexNeed flags of rows [rows.begin, rows.end) from the outcodes of rows begin - 2 .. end + 1
// (a triangle reaches one row around a vertex, a normal one more).
NeedCount vertex_needs(const GridLayout& layout, RowRange rows, std::span<const std::uint8_t> valid,
                       std::span<const std::uint8_t> outcode, std::span<std::uint8_t> need);

// After stage 3: kDraw again from the outcodes of the vertices' own heights, kept only where it
// was set (a point lies outside every plane its segment lies outside), kEvaluate unchanged.
NeedCount refine_draw_needs(const GridLayout& layout, RowRange rows,
                            std::span<const std::uint8_t> valid,
                            std::span<const std::uint8_t> outcode, std::span<std::uint8_t> need);

// The flags of rows as they are, counted.
NeedCount count_needs(const GridLayout& layout, RowRange rows, std::span<const std::uint8_t> valid,
                      std::span<const std::uint8_t> need);

// The flags with no culling: kEvaluate | kDraw at every valid vertex, or, with
// `include_invalid`, at every vertex of the rows, padding included (the work of a frame that
// skips nothing).
NeedCount vertex_needs_without_culling(const GridLayout& layout, RowRange rows,
                                       std::span<const std::uint8_t> valid, bool include_invalid,
                                       std::span<std::uint8_t> need);

}  // namespace relief
