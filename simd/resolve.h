// Stage 7, the attribute resolve of a tile (pipeline/tile_pass.h), as a Highway kernel in
// double lanes: for every covered pixel, the perspective-correct barycentrics at the pixel and
// at its two quad partners (raster::quad_weights), and the attributes and their derivatives
// interpolated from the winning triangle's vertices, with raster::resolve's operations in its
// order, rounded once to float. Bit-identical to the scalar resolve on every target.
#pragma once

#include <cstddef>
#include <cstdint>

namespace relief::simd {

// The triangles of a tile, one slot per triangle that wins a pixel (set up by the caller):
// raster::PerspectivePlane's coefficients k[i], ku[i], kv[i], and the slot's record of vertex
// values (gather_slot_records).
struct ResolveSlots {
  const double* k[3];
  const double* ku[3];
  const double* kv[3];
  const float* records;
};

// Per grid vertex, the streams the resolve interpolates (stage 2-5 buffers, float). nu,
// lambert (gradient mode's per-vertex Lambert term) and drop (a planet's curvature drop,
// core/planet_bend.h) may be null (not resolved); water_depth null resolves zero depths.
struct ResolveStreams {
  const float *dx, *dz, *height, *nx, *ny, *nz, *slope, *water_depth, *nu;
  const float* lambert = nullptr;
  const float* drop = nullptr;
};
inline constexpr int kResolveStreams = 11;

// A slot's record: the value of stream f (in ResolveStreams' order) at the triangle's vertex c
// at float 3 f + c (a null stream's values 0), padded to 40 floats. The resolve reads a
// pixel's values from its slot's record in 8-float loads: three for the plane's 24 values,
// four where nu or lambert is resolved, five where a planet's drop is, where gathering them
// from the streams took a gather each (the record is written once per slot, read by every
// pixel of it).
inline constexpr int kSlotRecordFloats = 40;
static_assert(3 * kResolveStreams <= kSlotRecordFloats);

// Fills records [0, count) (count * kSlotRecordFloats floats) from the slots' vertices.
void gather_slot_records(const ResolveStreams& streams, const std::int32_t* const vertex[3],
                         std::size_t count, float* records);

// The resolved fields (pipeline/tile_pass.h's TileAttributes<float>), written at covered
// pixels only; nu, lambert and drop only when their streams are not null.
struct ResolveTargets {
  float *dx, *dz, *height, *dx_ddx, *dx_ddy, *dz_ddx, *dz_ddy, *height_ddx, *height_ddy;
  float *nx, *ny, *nz, *slope, *water_depth, *nu;
  float* lambert = nullptr;  // written when streams.lambert is not null
  float* drop = nullptr;     // written when streams.drop is not null
};

// The window transform of the clip coordinates (raster::VertexPositions): X = x scale_x +
// w translate_x, Y likewise, W = w, in double.
struct WindowTransform {
  double scale_x, scale_y, translate_x, translate_y;
};

// raster::PerspectivePlane of slots [0, count) from their vertices' clip coordinates (float,
// per grid vertex): fills the k, ku, kv arrays that `slots` points to (writable here).
void set_up_planes(const float* clip_x, const float* clip_y, const float* clip_w,
                   const WindowTransform& window, const std::int32_t* const vertex[3],
                   std::size_t count, double* const k[3], double* const ku[3], double* const kv[3]);

// Pixel (x0 + i, y0 + j) of the rectangle has index j * stride + i in `slot` (the slot of the
// triangle that covers it, -1 where none does) and in the targets. `stride` is a multiple of
// 16 and at least the width: whole vectors of a row are read.
void resolve_rect(const ResolveSlots& slots, const ResolveStreams& streams,
                  const std::int32_t* slot, int x0, int y0, int width, int height, int stride,
                  const ResolveTargets& out);

}  // namespace relief::simd
