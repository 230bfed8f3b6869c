// A whole frame on all cores: stages 1-4 (frame_runner.h), stage 5 vertex transform, stage 6
// rasterisation of the projected grid, stage 7 resolve of the vertex normals, and, until the
// shading stage lands, a plain diagnostic shading: Lambert with the interpolated vertex
// normal under a fixed sun, and a sky gradient where no terrain covers the pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/lattice.h"
#include "core/scene.h"
#include "raster/rasterize.h"
#include "tools/frame_runner.h"

namespace relief {

struct FrameTimings {
  StageTimings terrain;
  double transform_ms = 0;  // stage 5
  double raster_ms = 0;     // stage 6
  double resolve_ms = 0;    // stage 7
  double shade_ms = 0;      // diagnostic shading and sRGB encoding
  raster::RasterStats raster;
};

struct RenderedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // sRGB, row 0 = bottom
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

TerrainFrame rasterize_terrain(const Scene& scene, const NoiseLattice& lattice,
                               FrameTimings& timings);

RenderedImage render_diagnostic_frame(const Scene& scene, const NoiseLattice& lattice,
                                      FrameTimings& timings);

// The raster state of a scene's frame: its viewport, back faces culled (the terrain's
// underside is never seen from above), GREATER depth test with depth cleared to 0.
raster::RasterState frame_raster_state(const Scene& scene);

}  // namespace relief
