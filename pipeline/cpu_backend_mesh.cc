// CpuBackend's GeoMipMapping mode (terrain.heightfield.geomipmap, core/heightfield/field_mesh.h):
// stage 2 selects the view's tiles (quadtree frustum culling, levels by screen-space error,
// occlusion culling) and stitches their mesh, whose vertices then fill the grid buffers in rows
// of kMeshRowVertices; stages 3 and 4 read the field at those vertices; from stage 5 on the
// frame is the projected grid's, drawing the mesh's index list. Every CPU backend runs the same
// portable loops here (the mesh's vertex stages are gathers from the lattice, a few percent of
// the frame), so the simd frame is the reference's, bit for bit.
#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/input_file.h"
#include "core/vertex_culling.h"
#include "pipeline/cpu_backend.h"
#include "pipeline/frame_mesh.h"
#include "pipeline/memory_budget.h"

namespace relief {

template <class Real>
raster::FrameTriangles CpuBackend<Real>::frame_triangles() const {
  if (mesh_mode()) {
    return raster::IndexedTriangles{mesh_.indices};
  }
  return triangles();
}

// Bytes a mesh vertex takes through the frame: its lattice ids, the grid buffers' twelve fields,
// the clip coordinates (and their float copy in double), the Lambert term, valid, need and
// outcode, and its values prepared for set-up (raster::PreparedVertices: 34 bytes); a triangle
// its three indices.
template <class Real>
constexpr std::uintmax_t kMeshVertexBytes = 2 * 4 + 17 * sizeof(Real) + 4 * 4 + 3 + 34;
constexpr std::uintmax_t kMeshTriangleBytes = 3 * sizeof(std::uint32_t);

template <class Real>
std::uintmax_t CpuBackend<Real>::check_mesh_memory(const geomipmap::Selection& selection) const {
  const auto [vertices, triangles] = mesh_size_bound(*field_mesh_, selection);
  const std::uintmax_t bytes = vertices * kMeshVertexBytes<Real> + triangles * kMeshTriangleBytes;
  if (bytes > request_.max_bin_bytes) {
    throw MemoryLimitError("the GeoMipMap mesh of this view (up to " + std::to_string(vertices) +
                           " vertices, " + std::to_string(triangles) + " triangles) needs up to " +
                           format_bytes(bytes) + ", more than the " +
                           format_bytes(request_.max_bin_bytes) +
                           " left of the memory budget; raise "
                           "terrain.heightfield.geomipmap.pixel_error");
  }
  return bytes;
}

template <class Real>
void CpuBackend<Real>::prepare_mesh() {
  const geomipmap::View view =
      frame_mesh_view(scene_, plan_, request_.skips.occluded_tiles);  // camera above the base
  const geomipmap::Selection selection = geomipmap::select_levels(field_mesh_->map, view);
  mesh_counts_ = selection.counts;
  mesh_bytes_ = check_mesh_memory(selection);  // the bins get what is left (tally_setup)
  mesh_ = geomipmap::stitched_mesh(field_mesh_->map, selection);
  plan_.layout = mesh_layout(mesh_.vertex_column.size());
  grid_ = GridBuffers<Real>(plan_.layout);
  need_.assign(plan_.layout.size(), 0);
}

template <class Real>
void CpuBackend<Real>::prepare_mesh_setup() {
  // Every mesh vertex is valid and drawn (padding is never indexed): no condition.
  const std::size_t vertices = mesh_.vertex_column.size();
  mesh_prepared_.resize((vertices + kMeshPreparedBlock - 1) / kMeshPreparedBlock);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mesh_prepared_.size(), 1),
      [&](const tbb::blocked_range<std::size_t>& blocks) {
        for (std::size_t b = blocks.begin(); b < blocks.end(); ++b) {
          setup_->prepare_vertices(raster_positions(), b * kMeshPreparedBlock,
                                   std::min(vertices, (b + 1) * kMeshPreparedBlock), {}, {},
                                   mesh_prepared_[b]);
        }
      },
      tbb::simple_partitioner());
}

template <class Real>
void CpuBackend<Real>::run_mesh(StageId id, RowRange rows) {
  const IndexRange range{plan_.layout.index(0, rows.begin), plan_.layout.index(0, rows.end)};
  NeedCount count;
  for (std::size_t k = range.begin; k < range.end && id != StageId::kProjectedDomain; ++k) {
    const std::uint64_t valid = grid_.valid[k];
    count.evaluate += valid;
    count.draw += valid;
    count.valid_draw += valid;
  }
  switch (id) {
    case StageId::kProjectedDomain:
      mesh_domain<Real>(*field_mesh_, mesh_, plan_.camera.position, range, grid_.domain());
      for (std::size_t k = range.begin; k < range.end; ++k) {
        need_[k] = grid_.valid[k] ? std::uint8_t(kEvaluate | kDraw) : std::uint8_t(0);
      }
      return;
    case StageId::kVertexNeeds:
      tally_rows(rows, count);
      return;
    case StageId::kFractal:
      mesh_heights<Real>(*field_mesh_, mesh_, camera_above_base(), range, grid_.height);
      tally_fbm(FbmWork{count.evaluate, 0});
      return;
    case StageId::kDrawNeeds:
      tally_draws(rows, count);
      return;
    case StageId::kSurface:
      mesh_surface<Real>(*field_mesh_, *field_texels_, mesh_, params_.surface.water_level,
                         params_.surface.water_enabled != 0, range, grid_.height, grid_.surface());
      return;
    default:  // the outcodes: none (units 0)
      return;
  }
}

template <class Real>
void CpuBackend<Real>::describe_mesh(StageTime& time) const {
  add_mesh_counters(*field_mesh_, mesh_counts_, std::uint64_t(mesh_.vertex_column.size()), time);
}

template <class Real>
std::vector<KernelChoice> CpuBackend<Real>::mesh_kernel_choices() const {
  static constexpr const char* kWhy =
      "the GeoMipMap mesh's vertices are gathers from the field's lattice (field_mesh.h), a "
      "few percent of the frame";
  std::vector<KernelChoice> out = {
      {StageId::kProjectedDomain, "mesh positions", KernelKind::kPortable, kWhy},
      {StageId::kFractal, "mesh heights", KernelKind::kPortable, kWhy},
      {StageId::kSurface, "mesh normals", KernelKind::kPortable, kWhy}};
  for (const KernelChoice& choice : kernels_.choices) {
    if (choice.stage > StageId::kSurface) {  // stages 5 on: the grid's kernels
      out.push_back(choice);
    }
  }
  // The portable loops are the reference backends' own kind: no reason to give there.
  if (kernels_.choices.empty() || request_.backend != Backend::kSimd) {
    for (KernelChoice& choice : out) {
      if (choice.stage <= StageId::kSurface) {
        choice.reason = "";
      }
    }
  }
  return out;
}

template std::vector<KernelChoice> CpuBackend<float>::mesh_kernel_choices() const;
template std::vector<KernelChoice> CpuBackend<double>::mesh_kernel_choices() const;
template raster::FrameTriangles CpuBackend<float>::frame_triangles() const;
template raster::FrameTriangles CpuBackend<double>::frame_triangles() const;
template std::uintmax_t CpuBackend<float>::check_mesh_memory(const geomipmap::Selection&) const;
template std::uintmax_t CpuBackend<double>::check_mesh_memory(const geomipmap::Selection&) const;
template void CpuBackend<float>::prepare_mesh_setup();
template void CpuBackend<double>::prepare_mesh_setup();
template void CpuBackend<float>::prepare_mesh();
template void CpuBackend<double>::prepare_mesh();
template void CpuBackend<float>::run_mesh(StageId, RowRange);
template void CpuBackend<double>::run_mesh(StageId, RowRange);
template void CpuBackend<float>::describe_mesh(StageTime&) const;
template void CpuBackend<double>::describe_mesh(StageTime&) const;

}  // namespace relief
