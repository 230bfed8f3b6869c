// The CPU backend: the stages of the table (stage_table.h) over the units of work the runner
// hands it, each through the kernel table of the frame (cpu_kernels.h): the portable loops of
// core/ and raster/ in float (the reference backend, the product's images) or double
// (reference-double, for accuracy comparisons), or the Highway kernels of simd/ (the simd
// backend, the same bytes as the reference), each fallback stated in the table.
//
// In double every per-vertex and per-pixel value is double: grid buffers, clip coordinates,
// resolved attributes, shading. Coverage is GL's rule on float window coordinates, so the
// rasteriser takes the double clip coordinates rounded once to float; the depth planes and the
// perspective barycentrics come from double positions.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/heightfield/field_mesh.h"
#include "core/octave_coordinates.h"
#include "core/shading_plan.h"
#include "core/sky_horizons.h"
#include "core/stage_params.h"
#include "core/sun_horizons.h"
#include "core/vertex_culling.h"
#include "core/water_reflection.h"
#include "pipeline/cpu_kernels.h"
#include "pipeline/frame_backend.h"
#include "pipeline/tile_pass.h"
#include "raster/bins.h"

namespace relief {

template <class Real>
class CpuBackend final : public FrameBackend {
 public:
  // `textures` may be empty when only stages 1-4 are run (relief stages); `sketch` is the
  // scene's terrain.sketch as loaded (null: the scene has none); `terrain_values` the grid of
  // stage 3 when it is not `lattice` (terrain.basis's composed grid; null: the lattice);
  // `field_mesh` terrain.heightfield.geomipmap's lattice and tiles: given, stages 2-6 draw its
  // GeoMipMap mesh instead of the projected grid (cpu_backend_mesh.cc); null: the grid.
  CpuBackend(const Scene& scene, const NoiseLattice& lattice,
             std::span<const ProtoTexture> textures, const FrameRequest& request,
             const HeightSketch* sketch = nullptr, const NoiseLattice* terrain_values = nullptr,
             const Skybox* skybox = nullptr, const FieldMesh* field_mesh = nullptr);

  void prepare(StageId id) override;
  std::size_t units(StageId id) const override;
  void run(StageId id, std::size_t begin, std::size_t end) override;
  void after(StageId id) override;
  void describe(StageId id, StageTime& time) const override;
  void finish(Frame& frame) override;

  // Restricts the tile stage to framebuffer rows [first_row, first_row + rows), both multiples
  // of raster::kTileSize (rows may end past the framebuffer): units(kTiles) counts the band's
  // tiles and the image prepared for them holds the band's rows alone (render_frame_bands).
  void set_band(int first_row, int rows);

  const FramePlan& plan() const { return plan_; }
  const GridBuffers<Real>& grid() const { return grid_; }
  GridBuffers<Real> take_grid() { return std::move(grid_); }

 private:
  raster::ClipVertices raster_positions() const;
  raster::GridTriangles triangles() const { return {plan_.layout, grid_.valid, need_}; }
  // The triangles the frame draws: the mesh's index list, or the grid's.
  raster::FrameTriangles frame_triangles() const;
  // GeoMipMapping (cpu_backend_mesh.cc): the view's tiles and stitched mesh, its vertices laid
  // out in the grid buffers (prepare of stage 2), and the vertex stages over its rows.
  bool mesh_mode() const { return field_mesh_ != nullptr; }
  double camera_above_base() const {
    return plan_.camera.position.y - scene_.terrain.base_height;  // in double
  }
  void prepare_mesh();
  // Before the mesh's set-up: its vertices prepared once (snapped, outcodes), in parallel blocks.
  void prepare_mesh_setup();
  // Refuses (MemoryLimitError) a selection whose mesh could exceed what is left of the budget.
  // Returns the bytes it may take.
  std::uintmax_t check_mesh_memory(const geomipmap::Selection& selection) const;
  void run_mesh(StageId id, RowRange rows);
  void describe_mesh(StageTime& time) const;
  // The kernel table's choices with stages 2-4's replaced by the mesh's portable loops.
  std::vector<KernelChoice> mesh_kernel_choices() const;
  int band_first_tile_row() const { return band_first_row_ / raster::kTileSize; }
  int band_tile_rows() const;
  bool planet() const { return params_.planet.enabled != 0; }
  void tally_rows(RowRange rows, const NeedCount& count);
  void tally_fbm(const FbmWork& work);
  void tally_draws(RowRange rows, const NeedCount& count);
  // After set-up: the triangles set up and the bins they need, refused (MemoryLimitError)
  // beyond what the frame's estimate left of the budget.
  void tally_setup();
  bool water_in_view() const;
  // Cast shadows, sky light and the water's reflections: the cache's rows to build (levels x
  // N), none without any or, with cast shadows alone, after sunset.
  std::size_t shadow_rows() const;
  bool sweeps_horizons() const;  // the cache's rows and columns swept (shadows, sky light)
  // After the draw flags: the levels the frame builds and the reflections read.
  void choose_cache_levels();
  void build_reflection_maxima();  // after the cache's heights, with reflections
  TileShadows<Real> tile_shadows() const;
  // The cache's three stages: its heights, the rows' sweeps, the columns' (sky light).
  void run_horizon_cache(StageId id, std::size_t begin, std::size_t end);
  void run_shadow_heights(std::size_t begin, std::size_t end);

  const Scene& scene_;
  const NoiseLattice& lattice_;         // the shading's noise (dithering, waves)
  const NoiseLattice& terrain_values_;  // stage 3's S: the lattice or the basis grid
  std::span<const ProtoTexture> textures_;
  const Skybox* skybox_;              // sky.skybox's faces, or null
  const FieldMesh* field_mesh_;       // terrain.heightfield.geomipmap's, or null
  const HeightSketch* field_texels_;  // the field's texels (the mesh's normals)
  geomipmap::Mesh mesh_;              // this frame's stitched mesh (mesh mode)
  geomipmap::SelectionCounts mesh_counts_;
  std::vector<raster::PreparedVertices> mesh_prepared_;  // blocks of kMeshPreparedBlock
  std::uintmax_t mesh_bytes_ = 0;  // what the mesh may take of the bins' budget
  FrameRequest request_;
  FramePlan plan_;
  TerrainParams<Real> params_;
  CpuKernels<Real> kernels_;  // chosen once from the backend and the scene's kind
  GridBuffers<Real> grid_;
  // Which vertices the frame needs (core/vertex_culling.h): the outcodes, then per vertex
  // kEvaluate | kDraw; with no skip at all every vertex is flagged.
  CullParams<Real> cull_;
  AlignedVector<std::uint8_t> outcode_, need_;
  // The work of the vertex stages, summed over their tasks under work_mutex_ (integer sums
  // and exact minima and maxima: the same for any split of the rows).
  mutable std::mutex work_mutex_;
  NeedCount needs_;                     // before stage 3, by the height bounds
  NeedCount draws_;                     // after it, by the heights
  double max_nu_ = 0;                   // largest nu of a vertex evaluated
  OctaveReach reach_;                   // how far each octave reaches (valid vertices)
  double min_drawn_height_ = HUGE_VAL;  // lowest height of a drawn vertex
  FbmWork fbm_work_;
  std::uint64_t transformed_ = 0;
  std::int32_t scene_octaves_ = 0;
  AlignedVector<Real> clip_x_, clip_y_, clip_z_, clip_w_;
  AlignedVector<Real> lambert_;  // gradient mode: each vertex's Lambert term (stage 5)
  // The rasteriser's float positions: the clip coordinates themselves in float, rounded once
  // in double (empty in float, where clip_* are used directly).
  AlignedVector<float> raster_x_, raster_y_, raster_z_, raster_w_;
  raster::RasterState state_;
  std::unique_ptr<raster::TriangleSetup> setup_;
  raster::TileGrid tiles_;
  std::vector<raster::SetupChunk> chunks_;
  raster::RasterStats raster_stats_;
  // Cast shadows (core/sun_horizons.h): the plan, its parameters, stage 3's parameters for the
  // cache (its own coordinate forms, every octave the levels sum), the cache and its work.
  ShadowPlan shadow_plan_;
  ShadowParams<Real> shadow_;
  FbmParams<Real> shadow_fbm_;
  SunHorizonCache<Real> horizons_;
  FbmWork shadow_fbm_work_;
  DrawnExtent drawn_;  // where the drawn triangles lie in the sun's frame
  HorizonWork horizon_work_;
  HorizonWork sky_work_;  // the columns' sweeps (sky light)
  // The water's reflections (core/water_reflection.h): the cache's parameters with the levels
  // the frame reads (shadow_level_range, whether or not it skips the others), and those
  // levels' blocks' largest heights.
  ShadowParams<Real> reflection_levels_;
  HeightBlockMaxima<Real> maxima_;
  ShadingPlan shading_plan_;
  ShadeParams<Real> shade_;
  FrameImage image_;
  TileTimes times_;
  std::unique_ptr<TilePass<Real>> tile_pass_;
  int band_first_row_ = 0;
  int band_rows_ = -1;  // -1: the whole framebuffer
};

// The raster state of a scene's frame: its viewport, back faces culled (the terrain's
// underside is never seen from above), GREATER depth test with depth cleared to 0.
raster::RasterState frame_raster_state(const Scene& scene);

}  // namespace relief
