// The reference backends: the scalar stages of core/ and raster/, in float (the product's
// images) or in double (for accuracy comparisons), over the units of work of the stage table.
//
// In double every per-vertex and per-pixel value is double: grid buffers, clip coordinates,
// resolved attributes, shading. Coverage is GL's rule on float window coordinates, so the
// rasteriser takes the double clip coordinates rounded once to float; the depth planes and the
// perspective barycentrics come from double positions.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "pipeline/frame_backend.h"
#include "pipeline/tile_pass.h"
#include "raster/bins.h"

namespace relief {

template <class Real>
class ReferenceBackend final : public FrameBackend {
 public:
  // `textures` may be empty when only stages 1-4 are run (relief stages).
  ReferenceBackend(const Scene& scene, const NoiseLattice& lattice,
                   std::span<const ProtoTexture> textures, const FrameRequest& request);

  void prepare(StageId id) override;
  std::size_t units(StageId id) const override;
  void run(StageId id, std::size_t begin, std::size_t end) override;
  void after(StageId id) override;
  void finish(Frame& frame) override;

  const FramePlan& plan() const { return plan_; }
  const GridBuffers<Real>& grid() const { return grid_; }
  GridBuffers<Real> take_grid() { return std::move(grid_); }

 private:
  raster::ClipVertices raster_positions() const;
  raster::GridTriangles triangles() const { return {plan_.layout, grid_.valid}; }

  const Scene& scene_;
  const NoiseLattice& lattice_;
  std::span<const ProtoTexture> textures_;
  FrameRequest request_;
  FramePlan plan_;
  TerrainParams<Real> params_;
  GridBuffers<Real> grid_;
  AlignedVector<Real> clip_x_, clip_y_, clip_z_, clip_w_;
  // The rasteriser's float positions: the clip coordinates themselves in float, rounded once
  // in double (empty in float, where clip_* are used directly).
  AlignedVector<float> raster_x_, raster_y_, raster_z_, raster_w_;
  raster::RasterState state_;
  std::unique_ptr<raster::TriangleSetup> setup_;
  raster::TileGrid tiles_;
  std::vector<raster::SetupChunk> chunks_;
  raster::RasterStats raster_stats_;
  ShadingPlan shading_plan_;
  ShadeParams<Real> shade_;
  FrameImage image_;
  TileTimes times_;
  std::unique_ptr<TilePass<Real>> tile_pass_;
};

// The raster state of a scene's frame: its viewport, back faces culled (the terrain's
// underside is never seen from above), GREATER depth test with depth cleared to 0.
raster::RasterState frame_raster_state(const Scene& scene);

}  // namespace relief
