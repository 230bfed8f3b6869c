// The frame's stages one after another over the whole frame, in float: every stage's output
// kept in full-size buffers (17 attribute planes between resolve and shading). This is the
// straightforward composition of the stage functions that the tile-fused back end
// (tile_pass.h) must reproduce bit for bit; tests and benchmarks use it, frames do not.
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/scene/scene.h"
#include "core/shade.h"
#include "core/sun_horizons.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"
#include "raster/resolve.h"

namespace relief {

// Stages 1-6 of a frame: the grid buffers, clip coordinates and visibility buffer.
struct TerrainFrame {
  FramePlan plan;
  GridBuffers<float> grid;
  AlignedVector<float> clip_x, clip_y, clip_z, clip_w;
  raster::RasterState state;
  raster::VisibilityBuffer visibility;
  raster::RasterStats raster;

  raster::ClipVertices clip() const { return {clip_x, clip_y, clip_z, clip_w}; }
  raster::GridTriangles triangles() const { return {plan.layout, grid.valid}; }
};

// Throws MemoryLimitError (memory_budget.h) when the rasteriser's bins exceed `limits`.
// `sketch`: the scene's terrain.sketch as loaded (null: none).
TerrainFrame rasterize_terrain(const Scene& scene, const NoiseLattice& lattice,
                               const raster::RasterLimits& limits = {},
                               const HeightSketch* sketch = nullptr);

// The same with the scene's resources (the lattice and the sketch).
TerrainFrame rasterize_terrain(const Scene& scene, const SceneResources& resources,
                               const raster::RasterLimits& limits = {});

// Stage 7 as stage 8 reads it: eight streams (dx, dz, height, nx, ny, nz, slope, water
// depth), with the derivatives of the first three (the texture LOD); and the view of the
// result that stage 8 takes.
raster::ResolvedFrame resolve_for_shading(const TerrainFrame& frame);
ShadingInputs shading_inputs(const TerrainFrame& frame, const raster::ResolvedFrame& resolved);

// The whole frame: sRGB image and linear radiance (FrameImage's srgb and linear).
FrameImage render_whole_frame(const Scene& scene, const SceneResources& resources);

// Cast shadows' horizon cache composed from core's functions (core/sun_horizons.h): the heights
// of levels [first, end) (end < 0: every level) by stage 3's portable fBm and sketch, then
// their rows swept. Empty where the plan is disabled or the sun has set.
template <class Real>
SunHorizonCache<Real> build_horizon_cache(const ShadowPlan& plan, const FramePlan& frame,
                                          const SceneResources& resources, int first = 0,
                                          int end = -1);

}  // namespace relief
