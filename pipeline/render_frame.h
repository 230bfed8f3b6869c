// A whole frame on all cores: stages 1-4 (frame_runner.h), 5 (vertex transform), 6
// (rasterisation of the projected grid), 7 (resolve of the attributes stage 8 reads), 8
// (proto-texture shading), then sRGB encoding. Each stage runs over fixed chunks with oneTBB,
// so the image is bit-identical for every thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/scene/scene.h"
#include "core/shade.h"
#include "pipeline/frame_runner.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"
#include "raster/resolve.h"

namespace relief {

struct FrameTimings {
  StageTimings terrain;
  double transform_ms = 0;  // stage 5
  double raster_ms = 0;     // stage 6
  double resolve_ms = 0;    // stage 7
  double shade_ms = 0;      // stage 8
  double encode_ms = 0;     // stage 9: sRGB encoding (file writing not included)
  raster::RasterStats raster;
};

// Stages 1-6 of a frame: the grid buffers, clip coordinates and visibility buffer.
struct TerrainFrame {
  FramePlan plan;
  GridBuffers<float> grid;
  AlignedVector<float> clip_x, clip_y, clip_z, clip_w;
  raster::RasterState state;
  raster::VisibilityBuffer visibility;

  raster::ClipVertices clip() const { return {clip_x, clip_y, clip_z, clip_w}; }
  raster::GridTriangles triangles() const { return {plan.layout, grid.valid}; }
};

// Throws MemoryLimitError (memory_budget.h) when the rasteriser's bins exceed `limits`.
TerrainFrame rasterize_terrain(const Scene& scene, const NoiseLattice& lattice,
                               FrameTimings& timings, const raster::RasterLimits& limits = {});

// Stage 7 as stage 8 reads it: eight streams (dx, dz, height, nx, ny, nz, slope, water
// depth), with the derivatives of the first three (the texture LOD); and the view of the
// result that stage 8 takes.
raster::ResolvedFrame resolve_for_shading(const TerrainFrame& frame);
ShadingInputs shading_inputs(const TerrainFrame& frame, const raster::ResolvedFrame& resolved);

struct RenderedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // sRGB, row 0 = bottom
  std::vector<float> linear;      // linear radiance (exposure applied), row 0 = bottom
};

RenderedImage render_frame(const Scene& scene, const SceneResources& resources,
                           FrameTimings& timings, const raster::RasterLimits& limits = {});

// The raster state of a scene's frame: its viewport, back faces culled (the terrain's
// underside is never seen from above), GREATER depth test with depth cleared to 0.
raster::RasterState frame_raster_state(const Scene& scene);

}  // namespace relief
