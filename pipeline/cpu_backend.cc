#include "pipeline/cpu_backend.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "core/det_math.h"
#include "core/fbm.h"
#include "core/input_file.h"
#include "core/limits.h"
#include "core/octave_coordinates.h"
#include "core/projected_domain.h"
#include "core/surface.h"
#include "core/terrain_stages.h"
#include "core/vertex_transform.h"
#include "pipeline/memory_budget.h"
#include "pipeline/parallel_rows.h"

namespace relief {

template <class Real>
CpuBackend<Real>::CpuBackend(const Scene& scene, const NoiseLattice& lattice,
                             std::span<const ProtoTexture> textures, const FrameRequest& request,
                             const HeightSketch* sketch, const NoiseLattice* terrain_values,
                             const Skybox* skybox, const FieldMesh* field_mesh)
    : scene_(scene),
      lattice_(lattice),
      terrain_values_(terrain_values ? *terrain_values : lattice),
      textures_(textures),
      skybox_(skybox),
      field_mesh_(field_mesh),
      field_texels_(sketch),
      request_(request),
      plan_(make_frame_plan(scene, terrain_values_, sketch, thread_pool_rows())),
      params_(make_terrain_params<Real>(plan_)),
      kernels_(cpu_kernels<Real>(request.backend, params_.planet.enabled != 0)),
      grid_(field_mesh ? GridLayout{} : plan_.layout),  // the mesh's: prepare_mesh
      cull_(make_cull_params<Real>(plan_)),
      need_(field_mesh ? 0 : plan_.layout.size()),
      scene_octaves_(params_.fbm.count),
      state_(frame_raster_state(scene)),
      tiles_(raster::make_tile_grid(state_)),
      shadow_plan_(make_shadow_plan(scene, plan_)),
      shadow_(make_shadow_params<Real>(shadow_plan_)) {
  shadow_.skip_lit = request.skips.lit_shadows ? 1 : 0;
  // Without its mesh the field would be drawn as the projected grid without a word (relief
  // stages, which shades nothing, runs the grid's stages 1-4 on purpose).
  if (scene.terrain.heightfield && scene.terrain.heightfield->geomipmap && !textures.empty() &&
      field_mesh == nullptr) {
    throw std::invalid_argument(
        "cpu backend: terrain.heightfield.geomipmap is set; no field mesh was built");
  }
}

template <class Real>
std::size_t CpuBackend<Real>::units(StageId id) const {
  switch (id) {
    case StageId::kOutcodes:
      if (mesh_mode())  // the quadtree culled the tiles (prepare_mesh)
        return 0;
      // A planet frame evaluates every valid vertex: the height bounds' segments are vertical
      // in the unbent frame, not in the bent one (docs/planet.md).
      return request_.skips.unseen_vertices && !planet()
                 ? static_cast<std::size_t>(plan_.layout.height)
                 : 0;
    case StageId::kDrawOutcodes:
      return request_.skips.unseen_vertices && !mesh_mode()
                 ? static_cast<std::size_t>(plan_.layout.height)
                 : 0;
    case StageId::kProjectedDomain:
    case StageId::kVertexNeeds:
    case StageId::kDrawNeeds:
    case StageId::kFractal:
    case StageId::kSurface:
      return static_cast<std::size_t>(plan_.layout.height);
    case StageId::kVertexTransform:
      return plan_.layout.size();
    case StageId::kTriangleSetup:
    case StageId::kBinning:
      return raster::setup_chunk_count(frame_triangles().count());
    case StageId::kShadowHeights:
      return shadow_rows();
    case StageId::kSunHorizons:
      return sweeps_horizons() ? shadow_rows() : 0;
    case StageId::kSkyHorizons:  // as many columns as rows
      return shadow_.sky != 0 ? shadow_rows() : 0;
    case StageId::kTiles:
      return static_cast<std::size_t>(band_tile_rows()) * tiles_.columns;
  }
  return 0;
}

template <class Real>
void CpuBackend<Real>::set_band(int first_row, int rows) {
  band_first_row_ = first_row;
  band_rows_ = rows;
}

template <class Real>
int CpuBackend<Real>::band_tile_rows() const {
  if (band_rows_ < 0) {
    return tiles_.rows;
  }
  const int first = band_first_tile_row();
  const int end = std::min(tiles_.rows, (band_first_row_ + band_rows_) / raster::kTileSize);
  return std::max(0, end - first);
}

template <class Real>
raster::ClipVertices CpuBackend<Real>::raster_positions() const {
  if constexpr (std::is_same_v<Real, float>) {
    return {clip_x_, clip_y_, clip_z_, clip_w_};
  } else {
    return {raster_x_, raster_y_, raster_z_, raster_w_};
  }
}

template <class Real>
void CpuBackend<Real>::run(StageId id, std::size_t begin, std::size_t end) {
  const RowRange rows{static_cast<int>(begin), static_cast<int>(end)};
  if (mesh_mode() && id <= StageId::kSurface) {
    run_mesh(id, rows);
    return;
  }
  switch (id) {
    case StageId::kProjectedDomain:
      if (planet()) {
        kernels_.project_planet_domain(params_.domain, params_.planet, params_.domain_rows, rows,
                                       grid_.domain());
      } else {
        kernels_.project_domain(params_.domain, params_.domain_rows, rows, grid_.domain());
      }
      if (request_.octave_count_rule) {  // the ground truth's (eval/distance_lod.h)
        request_.octave_count_rule->apply(rows, grid_);
      }
      return;
    case StageId::kOutcodes:
    case StageId::kDrawOutcodes: {
      // Before stage 3 the segments of the height bounds, after it the vertices' own heights
      // (on a planet their bent positions).
      const std::span<const Real> height =
          id == StageId::kOutcodes ? std::span<const Real>{}
                                   : std::span<const Real>(planet() ? grid_.bent_y : grid_.height);
      const std::span<const Real> x = planet() ? grid_.bent_x : grid_.dx;
      const std::span<const Real> z = planet() ? grid_.bent_z : grid_.dz;
      kernels_.vertex_outcodes(cull_, rows, x, z, height, grid_.valid, outcode_);
      return;
    }
    case StageId::kDrawNeeds:
      tally_draws(rows, request_.skips.unseen_vertices
                            ? refine_draw_needs(plan_.layout, rows, grid_.valid, outcode_, need_)
                            : count_needs(plan_.layout, rows, grid_.valid, need_));
      return;
    case StageId::kVertexNeeds: {
      const FrameSkips& skips = request_.skips;
      tally_rows(rows, skips.unseen_vertices && !planet()
                           ? vertex_needs(plan_.layout, rows, grid_.valid, outcode_, need_)
                           : vertex_needs_without_culling(plan_.layout, rows, grid_.valid,
                                                          !skips.invalid_vertices, need_));
      return;
    }
    case StageId::kFractal: {
      const IndexRange range{plan_.layout.index(0, rows.begin), plan_.layout.index(0, rows.end)};
      tally_fbm(kernels_.fractal(params_.fbm, terrain_values_, range, grid_.dx, grid_.dz, grid_.nu,
                                 need_, grid_.height));
      if (params_.sketch.enabled != 0 && plan_.terrain.sketch != nullptr) {  // §3's base
        kernels_.sketch(params_.sketch, plan_.terrain.sketch->heights, range, grid_.dx, grid_.dz,
                        grid_.nu, need_, grid_.height);
      }
      if (planet()) {  // the bend, once the rows' heights are known (planet_bend.h)
        kernels_.bend_vertices(params_.planet, range, grid_.dx, grid_.dz, grid_.height, grid_.valid,
                               grid_.bent());
      }
      return;
    }
    case StageId::kSurface: {
      kernels_.surface(params_.surface, rows, surface_inputs(grid_, need_), grid_.surface());
      if (planet()) {  // the unbent frame's normals into the bent one
        kernels_.bend_normals(
            params_.planet,
            IndexRange{plan_.layout.index(0, rows.begin), plan_.layout.index(0, rows.end)},
            grid_.dx, grid_.dz, grid_.valid, grid_.nx, grid_.ny, grid_.nz);
      }
      return;
    }
    case StageId::kShadowHeights:
    case StageId::kSunHorizons:
    case StageId::kSkyHorizons:
      run_horizon_cache(id, begin, end);
      return;
    case StageId::kVertexTransform: {
      const ClipSpans<Real> clip{clip_x_, clip_y_, clip_z_, clip_w_};
      // On a planet the bent positions (planet_bend.h), through the same kernels.
      const std::span<const Real> x = planet() ? grid_.bent_x : grid_.dx;
      const std::span<const Real> y = planet() ? grid_.bent_y : grid_.height;
      const std::span<const Real> z = planet() ? grid_.bent_z : grid_.dz;
      kernels_.transform(params_.transform, IndexRange{begin, end}, x, z, y, need_, clip);
      if (params_.transform.gouraud != 0) {  // Gouraud shading lights the vertex here
        kernels_.light_vertices(params_.transform, IndexRange{begin, end}, grid_.nx, grid_.ny,
                                grid_.nz, need_, lambert_);
      }
      std::uint64_t transformed = 0;
      for (std::size_t k = begin; k < end; ++k) {
        transformed += (need_[k] & kDraw) != 0;
      }
      {
        const std::lock_guard<std::mutex> lock(work_mutex_);
        transformed_ += transformed;
      }
      if constexpr (!std::is_same_v<Real, float>) {
        for (std::size_t k = begin; k < end; ++k) {
          raster_x_[k] = static_cast<float>(clip_x_[k]);
          raster_y_[k] = static_cast<float>(clip_y_[k]);
          raster_z_[k] = static_cast<float>(clip_z_[k]);
          raster_w_[k] = static_cast<float>(clip_w_[k]);
        }
      }
      return;
    }
    case StageId::kTriangleSetup:
      for (std::size_t c = begin; c < end; ++c) {
        if (mesh_mode()) {
          raster::setup_indexed_chunk(*setup_, raster_positions(), {mesh_.indices}, mesh_prepared_,
                                      kMeshPreparedBlock, c, chunks_[c]);
        } else {
          raster::setup_chunk(*setup_, raster_positions(), triangles(), c, chunks_[c]);
        }
      }
      return;
    case StageId::kBinning:
      for (std::size_t c = begin; c < end; ++c) {
        raster::bin_chunk(chunks_[c], tiles_);
      }
      return;
    case StageId::kTiles: {
      const std::size_t first = std::size_t(band_first_tile_row()) * tiles_.columns;
      for (std::size_t tile = first + begin; tile < first + end; ++tile) {
        tile_pass_->run(chunks_, tiles_, static_cast<int>(tile), times_,
                        request_.skips.empty_tiles);
      }
      return;
    }
  }
}

template <class Real>
void CpuBackend<Real>::prepare(StageId id) {
  switch (id) {
    case StageId::kProjectedDomain:
      if (mesh_mode()) {
        prepare_mesh();
      }
      return;
    case StageId::kOutcodes:
      outcode_.resize(request_.skips.unseen_vertices ? plan_.layout.size() : 0);
      return;
    case StageId::kFractal:
      if (planet()) {
        grid_.allocate_bent();
      }
      return;
    case StageId::kShadowHeights:
      if (shadow_rows() > 0) {
        shadow_fbm_ = make_fbm_params<Real>(plan_.terrain);
        choose_coordinate_forms(plan_.terrain, shadow_octave_reach(shadow_plan_), shadow_fbm_);
        horizons_.allocate(shadow_plan_.resolution, shadow_.first_level, shadow_.end_level,
                           shadow_.enabled != 0 && shadow_.sun_set == 0, shadow_.sky != 0);
      }
      return;
    case StageId::kVertexTransform: {
      const std::size_t vertices = plan_.layout.size();
      for (AlignedVector<Real>* v : {&clip_x_, &clip_y_, &clip_z_, &clip_w_}) {
        v->resize(vertices);
      }
      if constexpr (!std::is_same_v<Real, float>) {
        for (AlignedVector<float>* v : {&raster_x_, &raster_y_, &raster_z_, &raster_w_}) {
          v->resize(vertices);
        }
      }
      // Gradient mode lights the vertices in this stage (gradient_shade.h): its flag and the
      // sun from the frame's shading plan.
      add_gouraud_lighting(make_shading_plan(scene_, plan_, lattice_.size), params_.transform);
      lambert_.resize(params_.transform.gouraud != 0 ? vertices : 0);
      return;
    }
    case StageId::kTriangleSetup:
      setup_ = std::make_unique<raster::TriangleSetup>(state_);
      if (kernels_.snap != nullptr) {
        setup_->set_snap_kernels(kernels_.snap);
      }
      chunks_.resize(raster::setup_chunk_count(frame_triangles().count()));
      if (mesh_mode()) {
        prepare_mesh_setup();
      }
      return;
    case StageId::kTiles: {
      // Stage 8's plan and the frame's outputs.
      shading_plan_ = make_shading_plan(scene_, plan_, lattice_.size);
      shade_ = make_shade_params<Real>(shading_plan_);
      add_planet_shading(plan_, scene_.terrain.base_height, shade_);
      apply_skips(request_.skips, water_in_view(), shade_);
      shade_.cloud_steps = request_.cloud_steps;  // 1 ... kMaxCloudSteps (render_with)
      const int rows = band_rows_ < 0
                           ? state_.height
                           : std::max(0, std::min(state_.height, band_first_row_ + band_rows_) -
                                             band_first_row_);
      const std::size_t pixels = std::size_t(state_.width) * rows;
      const FrameOutputs& o = request_.outputs;
      image_ = FrameImage{};
      image_.width = state_.width;
      image_.height = rows;
      image_.srgb.assign(3 * pixels, 0);
      image_.linear.assign(o.linear ? 3 * pixels : 0, 0.0f);
      image_.depth.assign(o.depth ? pixels : 0, state_.depth_clear);
      image_.primitive.assign(o.primitive ? pixels : 0, raster::kNoPrimitive);
      image_.normal.assign(o.normal ? 3 * pixels : 0, 0.0f);
      image_.world_height.assign(o.world_height ? pixels : 0, 0.0f);
      image_.octaves.assign(o.octaves ? pixels : 0, 0.0f);
      // On a planet (dx, dz) are the bent ones, the height stays the elevation's (materials
      // and water are radial) and the drop puts the shaded position on the sphere.
      const bool bent = planet();
      const VertexStreams<Real> streams{
          clip_x_,
          clip_y_,
          clip_w_,
          bent ? grid_.bent_x : grid_.dx,
          bent ? grid_.bent_z : grid_.dz,
          grid_.height,
          grid_.nx,
          grid_.ny,
          grid_.nz,
          grid_.slope,
          grid_.water_depth,
          grid_.nu,
          bent ? std::span<const Real>(grid_.bent_drop) : std::span<const Real>{},
          lambert_};
      if (shade_.skybox != 0 && skybox_ == nullptr) {
        // The sky would fall back to the gradient without a word (GL refuses it too).
        throw std::invalid_argument("cpu backend: sky.skybox is set; no faces were loaded");
      }
      tile_pass_ = std::make_unique<TilePass<Real>>(
          state_, frame_triangles(), streams, shade_, ShadeResources{&lattice_, textures_, skybox_},
          o, plan_.camera.position.y, image_, kernels_.tiles, band_rows_ < 0 ? 0 : band_first_row_,
          tile_shadows());
      return;
    }
    default:
      return;
  }
}

template <class Real>
void CpuBackend<Real>::after(StageId id) {
  switch (id) {
    case StageId::kVertexNeeds:
      // §4.1: a vertex sums floor(nu) octaves and a fraction of the next, so the frame's
      // table needs ceil(max nu) of them (nu >= 0).
      if (request_.skips.unused_octaves) {
        params_.fbm.count = static_cast<std::int32_t>(
            std::min(double(scene_octaves_), std::ceil(max_nu_)));  // in [0, scene's count]
      }
      choose_coordinate_forms(plan_.terrain, reach_, params_.fbm);
      return;
    case StageId::kShadowHeights:
      build_reflection_maxima();
      return;
    case StageId::kDrawNeeds:
      params_.surface.water_enabled = water_in_view() ? 1 : 0;
      choose_cache_levels();
      return;
    case StageId::kTriangleSetup:
      tally_setup();
      return;
    default:
      return;
  }
}

template <class Real>
void CpuBackend<Real>::finish(Frame& frame) {
  frame.image = std::move(image_);
  if (mesh_mode())  // the mesh's stable triangle numbers: the same with occlusion culling off
    geomipmap::stable_primitive_ids(mesh_, frame.image.primitive);
  frame.stats.raster = raster_stats_;
  frame.stats.kernels = kernel_reports(mesh_mode() ? mesh_kernel_choices() : kernels_.choices,
                                       std::is_same_v<Real, double>);
  // The parts of the fused stage: CPU time summed over the threads that ran tiles.
  const auto part = [](const char* name, const std::atomic<std::int64_t>& ns) {
    return StageTime{name, double(ns.load()) * 1e-6, true, {}};
  };
  frame.stats.tile_parts = {
      part("raster (CPU)", times_.raster_ns), part("resolve (CPU)", times_.resolve_ns),
      part("shadow (CPU)", times_.shadow_ns), part("shade (CPU)", times_.shade_ns),
      part("encode (CPU)", times_.encode_ns)};
}

template class CpuBackend<float>;
template class CpuBackend<double>;

}  // namespace relief
