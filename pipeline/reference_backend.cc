#include "pipeline/reference_backend.h"

#include <algorithm>
#include <type_traits>

#include "core/fbm.h"
#include "core/input_file.h"
#include "core/projected_domain.h"
#include "core/surface.h"
#include "core/terrain_stages.h"
#include "core/vertex_transform.h"
#include "pipeline/memory_budget.h"

namespace relief {

raster::RasterState frame_raster_state(const Scene& scene) {
  raster::RasterState state;
  state.width = scene.viewport.width;
  state.height = scene.viewport.height;
  state.viewport = {0.0, 0.0, double(scene.viewport.width), double(scene.viewport.height)};
  state.cull = raster::CullMode::kBack;
  state.depth_test = raster::DepthTest::kGreater;
  state.depth_clear = 0.0f;
  return state;
}

template <class Real>
ReferenceBackend<Real>::ReferenceBackend(const Scene& scene, const NoiseLattice& lattice,
                                         std::span<const ProtoTexture> textures,
                                         const FrameRequest& request)
    : scene_(scene),
      lattice_(lattice),
      textures_(textures),
      request_(request),
      plan_(make_frame_plan(scene, lattice)),
      params_(make_terrain_params<Real>(plan_)),
      grid_(plan_.layout),
      state_(frame_raster_state(scene)),
      tiles_(raster::make_tile_grid(state_)) {}

template <class Real>
std::size_t ReferenceBackend<Real>::units(StageId id) const {
  switch (id) {
    case StageId::kProjectedDomain:
    case StageId::kFractal:
    case StageId::kSurface:
      return static_cast<std::size_t>(plan_.layout.height);
    case StageId::kVertexTransform:
      return plan_.layout.size();
    case StageId::kTriangleSetup:
    case StageId::kBinning:
      return raster::setup_chunk_count(triangles().count());
    case StageId::kTiles:
      return static_cast<std::size_t>(tiles_.count());
  }
  return 0;
}

template <class Real>
raster::ClipVertices ReferenceBackend<Real>::raster_positions() const {
  if constexpr (std::is_same_v<Real, float>) {
    return {clip_x_, clip_y_, clip_z_, clip_w_};
  } else {
    return {raster_x_, raster_y_, raster_z_, raster_w_};
  }
}

template <class Real>
void ReferenceBackend<Real>::run(StageId id, std::size_t begin, std::size_t end) {
  const RowRange rows{static_cast<int>(begin), static_cast<int>(end)};
  switch (id) {
    case StageId::kProjectedDomain:
      project_domain<Real>(params_.domain, params_.row_descents, rows, grid_.domain());
      return;
    case StageId::kFractal:
      evaluate_fbm_rows<Real>(params_.fbm, lattice_, rows, grid_);
      return;
    case StageId::kSurface:
      surface_pass<Real>(params_.surface, rows, surface_inputs(grid_), grid_.surface());
      return;
    case StageId::kVertexTransform:
      transform_vertices<Real>(params_.transform, IndexRange{begin, end}, grid_.dx, grid_.dz,
                               grid_.height, ClipSpans<Real>{clip_x_, clip_y_, clip_z_, clip_w_});
      if constexpr (!std::is_same_v<Real, float>) {
        for (std::size_t k = begin; k < end; ++k) {
          raster_x_[k] = static_cast<float>(clip_x_[k]);
          raster_y_[k] = static_cast<float>(clip_y_[k]);
          raster_z_[k] = static_cast<float>(clip_z_[k]);
          raster_w_[k] = static_cast<float>(clip_w_[k]);
        }
      }
      return;
    case StageId::kTriangleSetup:
      for (std::size_t c = begin; c < end; ++c) {
        raster::setup_chunk(*setup_, raster_positions(), triangles(), c, chunks_[c]);
      }
      return;
    case StageId::kBinning:
      for (std::size_t c = begin; c < end; ++c) {
        raster::bin_chunk(chunks_[c], tiles_);
      }
      return;
    case StageId::kTiles:
      for (std::size_t tile = begin; tile < end; ++tile) {
        tile_pass_->run(chunks_, tiles_, static_cast<int>(tile), times_);
      }
      return;
  }
}

template <class Real>
void ReferenceBackend<Real>::prepare(StageId id) {
  switch (id) {
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
      return;
    }
    case StageId::kTriangleSetup:
      setup_ = std::make_unique<raster::TriangleSetup>(state_);
      chunks_.resize(raster::setup_chunk_count(triangles().count()));
      return;
    case StageId::kTiles: {
      // Stage 8's plan and the frame's outputs.
      shading_plan_ = make_shading_plan(scene_, plan_, lattice_.size);
      shade_ = make_shade_params<Real>(shading_plan_);
      const std::size_t pixels = std::size_t(state_.width) * state_.height;
      const FrameOutputs& o = request_.outputs;
      image_.width = state_.width;
      image_.height = state_.height;
      image_.srgb.assign(3 * pixels, 0);
      image_.linear.assign(o.linear ? 3 * pixels : 0, 0.0f);
      image_.depth.assign(o.depth ? pixels : 0, state_.depth_clear);
      image_.primitive.assign(o.primitive ? pixels : 0, raster::kNoPrimitive);
      image_.normal.assign(o.normal ? 3 * pixels : 0, 0.0f);
      image_.world_height.assign(o.world_height ? pixels : 0, 0.0f);
      image_.octaves.assign(o.octaves ? pixels : 0, 0.0f);
      const VertexStreams<Real> streams{clip_x_,  clip_y_,      clip_w_,           grid_.dx,
                                        grid_.dz, grid_.height, grid_.nx,          grid_.ny,
                                        grid_.nz, grid_.slope,  grid_.water_depth, grid_.nu};
      tile_pass_ = std::make_unique<TilePass<Real>>(state_, triangles(), streams, shade_,
                                                    ShadeResources{&lattice_, textures_}, o,
                                                    plan_.camera.position.y, image_);
      return;
    }
    default:
      return;
  }
}

template <class Real>
void ReferenceBackend<Real>::after(StageId id) {
  switch (id) {
    case StageId::kTriangleSetup: {
      raster_stats_.triangles = triangles().count();
      for (const raster::SetupChunk& chunk : chunks_) {
        raster_stats_.setup += chunk.triangles.size();
      }
      const raster::BinSize bins = raster::bin_size(chunks_, tiles_);
      raster_stats_.bin_entries = bins.entries;
      raster_stats_.bin_bytes = bins.bytes;
      if (bins.bytes > request_.max_bin_bytes) {
        raster_stats_.bins_refused = true;
        throw MemoryLimitError("the rasteriser's bins for this frame need " +
                               format_bytes(bins.bytes) + ", more than the " +
                               format_bytes(request_.max_bin_bytes) +
                               " left of the memory budget; lower viewport.width/height");
      }
      return;
    }
    default:
      return;
  }
}

template <class Real>
void ReferenceBackend<Real>::finish(Frame& frame) {
  frame.image = std::move(image_);
  frame.stats.raster = raster_stats_;
  // The parts of the fused stage: CPU time summed over the threads that ran tiles.
  const auto ms = [](const std::atomic<std::int64_t>& ns) { return double(ns.load()) * 1e-6; };
  frame.stats.tile_parts = {{"raster (CPU)", ms(times_.raster_ns)},
                            {"resolve (CPU)", ms(times_.resolve_ns)},
                            {"shade (CPU)", ms(times_.shade_ns)},
                            {"encode (CPU)", ms(times_.encode_ns)}};
}

template class ReferenceBackend<float>;
template class ReferenceBackend<double>;

}  // namespace relief
