#include "pipeline/gl_frame_mesh.h"

#include <algorithm>
#include <bit>
#include <mutex>
#include <optional>
#include <string>

#include "core/limits.h"
#include "gpu/gl_checks.h"
#include "pipeline/gl_backend.h"
#include "pipeline/memory_budget.h"

namespace relief {

namespace {

// Bytes the GL side holds for a mesh (host memory under llvmpipe, the GPU's otherwise: counted
// either way, as job_memory.cc counts the grid's): per vertex its lattice ids on the host and
// in the uploaded buffer (8 each) and the driver's transformed vertex
// (llvmpipe keeps the vertex shader's outputs: 192, job_memory.cc's figure); per vertex of the
// padded streams ten floats and the valid byte (41); per triangle its indices on the host and
// in the index buffer (12 each).
constexpr std::uintmax_t kGlMeshVertexBytes = 8 + 8 + 192;
constexpr std::uintmax_t kGlStreamVertexBytes = 41;
constexpr std::uintmax_t kGlMeshTriangleBytes = 12 + 12;

// The streams' rows for a mesh of `vertices`: the kept streams' where they hold it in at most
// four times its rows (so that a mesh that grows and shrinks by less keeps them), else the
// power of two at or above its rows (at least 2: a drawn grid's least).
std::uintmax_t stream_rows(std::uintmax_t vertices, std::optional<GridLayout> kept) {
  const std::uintmax_t rows =
      std::max<std::uintmax_t>(2, (vertices + kMeshRowVertices - 1) / kMeshRowVertices);
  if (kept && kept->width == kMeshRowVertices && std::uintmax_t(kept->height) >= rows &&
      std::uintmax_t(kept->height) <= 4 * rows) {
    return std::uintmax_t(kept->height);
  }
  return std::bit_ceil(rows);  // rows <= 2^64 / 4096: representable
}

// Refuses a view whose mesh (at most `size`) could exceed what the budget leaves the frame
// (MemoryLimitError) or the streams' largest grid (limits::kMaxGridSide rows), before the mesh
// is built; returns the streams' rows.
int check_mesh_size(const MeshSize& size, const FrameRequest& request,
                    std::optional<GridLayout> kept) {
  const std::uintmax_t rows = stream_rows(size.vertices, kept);
  const std::string mesh = "the GeoMipMap mesh of this view (up to " +
                           std::to_string(size.vertices) + " vertices, " +
                           std::to_string(size.triangles) + " triangles)";
  if (rows > std::uintmax_t(limits::kMaxGridSide)) {
    throw GlBackendError(mesh + " needs more than the GL backend's " +
                         std::to_string(std::uintmax_t(limits::kMaxGridSide) * kMeshRowVertices) +
                         " vertices; raise terrain.heightfield.geomipmap.pixel_error");
  }
  const std::uintmax_t bytes = size.vertices * kGlMeshVertexBytes +
                               rows * kMeshRowVertices * kGlStreamVertexBytes +
                               size.triangles * kGlMeshTriangleBytes;
  if (bytes > request.max_bin_bytes) {
    throw MemoryLimitError(mesh + " needs up to " + format_bytes(bytes) +
                           " on the GL side, more than the " + format_bytes(request.max_bin_bytes) +
                           " left of the memory budget; raise "
                           "terrain.heightfield.geomipmap.pixel_error");
  }
  return int(rows);  // <= limits::kMaxGridSide
}

}  // namespace

gpu::GlTerrain* GlFrameMesh::run(GlSceneCache& cache, StageId id, const Scene& scene,
                                 const SceneResources& resources, const FramePlan& plan,
                                 const FrameRequest& request, const SurfaceParams<float>& surface) {
  const FieldMesh& field = *resources.field_mesh;
  const glm::dvec3& camera = plan.camera.position;
  if (id == StageId::kProjectedDomain) {
    terrain_ = nullptr;
    const geomipmap::Selection selection = geomipmap::select_levels(
        field.map, frame_mesh_view(scene, plan, request.skips.occluded_tiles));
    const int rows =
        check_mesh_size(mesh_size_bound(field, selection), request, cache.terrain_layout());
    counts_ = selection.counts;
    mesh_ = geomipmap::stitched_mesh(field.map, selection);
    if (mesh_.vertex_column.empty()) {
      return nullptr;  // every tile culled: the background alone
    }
    const GridLayout layout = make_grid_layout(kMeshRowVertices, rows);
    terrain_ = &cache.terrain(layout, resources);
    terrain_->set_mesh_vertices(mesh_.vertex_column, mesh_.vertex_row);
    terrain_->mesh_domain(field, camera.x, camera.z);
    gpu::check_gl("stage 2 (mesh.comp)");
  } else if (terrain_ != nullptr && id == StageId::kFractal) {
    terrain_->mesh_heights(camera.y - scene.terrain.base_height);  // in double
    gpu::check_gl("stage 3 (mesh.comp)");
  } else if (terrain_ != nullptr && id == StageId::kSurface) {
    terrain_->mesh_surface(field, surface);
    gpu::check_gl("stage 4 (mesh.comp)");
  }
  return terrain_;
}

GridBuffers<float> gl_mesh_stages(const Scene& scene, const SceneResources& resources,
                                  const FrameSkips& skips) {
  if (resources.field_mesh_or_null() == nullptr || resources.sketch_or_null() == nullptr) {
    throw GlBackendError("gl_mesh_stages: the scene's resources hold no field mesh");
  }
  GlSession& s = gl_session();
  const std::lock_guard<std::mutex> lock(s.mutex);
  const FramePlan plan =
      make_frame_plan(scene, resources.terrain_values(), resources.sketch_or_null());
  const SurfaceParams<float> surface = make_terrain_params<float>(plan).surface;
  FrameRequest request;
  request.skips = skips;
  const GlCurrent current(s);
  GridBuffers<float> grid(mesh_layout(0));  // replaced by the streams' layout once drawn
  try {
    GlFrameMesh mesh;
    gpu::GlTerrain* terrain = nullptr;
    for (const StageId id : {StageId::kProjectedDomain, StageId::kFractal, StageId::kSurface}) {
      terrain = mesh.run(s.cache, id, scene, resources, plan, request, surface);
    }
    if (terrain != nullptr) {
      grid = GridBuffers<float>(terrain->layout());
      terrain->read_all(grid);
    }
  } catch (const MemoryLimitError&) {
    throw;
  } catch (const std::exception& e) {
    s.cache.forget_scene();  // half-written streams: the next frame makes them again
    throw GlBackendError(std::string("the GL backend's GeoMipMap mesh: ") + e.what());
  }
  return grid;
}

}  // namespace relief
