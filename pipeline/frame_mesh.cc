#include "pipeline/frame_mesh.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "core/stage_params.h"

namespace relief {

geomipmap::View frame_mesh_view(const Scene& scene, const FramePlan& plan,
                                bool occluded_tiles_skip) {
  const GeoMipMapSettings& settings = *scene.terrain.heightfield->geomipmap;
  geomipmap::View view;
  view.camera = plan.camera;
  view.camera.position.y = plan.camera.position.y - scene.terrain.base_height;  // in double
  view.width = scene.viewport.width;
  view.height = scene.viewport.height;
  view.pixel_error = settings.pixel_error;
  // Occlusion culling removes only tiles no pixel sees (geomipmap_select.cc): a skip.
  view.occlusion = settings.occlusion && occluded_tiles_skip;
  return view;
}

MeshSize mesh_size_bound(const FieldMesh& field, const geomipmap::Selection& selection) {
  MeshSize size;
  const int cells = field.map.tile_cells;
  for (std::size_t tile = 0; tile < selection.drawn.size(); ++tile) {
    if (selection.drawn[tile] != 0) {
      const std::uintmax_t side = std::uintmax_t(cells >> selection.level[tile]);
      size.vertices += (side + 1) * (side + 1);
      size.triangles += 2 * side * side;
    }
  }
  return size;
}

void add_mesh_counters(const FieldMesh& field, const geomipmap::SelectionCounts& c,
                       std::uint64_t vertices, StageTime& time) {
  const auto count = [&](std::string name, std::uint64_t value) {
    time.counters.push_back({std::move(name), value});
  };
  count("GeoMipMap tiles", std::uint64_t(field.map.tiles.size()));
  count("quadtree nodes visited", c.nodes_visited);
  count("quadtree nodes culled", c.nodes_culled);
  count("tiles outside the frustum", c.tiles_culled);
  count("occlusion cells covered by a floor", c.occlusion_cells);
  count("tiles occluded", c.tiles_occluded);
  count("tiles drawn", c.tiles_drawn);
  for (int level = 0; level < field.map.levels; ++level) {
    count("tiles drawn at level " + std::to_string(level), c.tiles_per_level[level]);
  }
  count("mesh vertices", vertices);
}

MeshStages cpu_mesh_stages(const Scene& scene, const SceneResources& resources,
                           const FrameSkips& skips) {
  const FieldMesh* field = resources.field_mesh_or_null();
  if (field == nullptr || resources.sketch_or_null() == nullptr) {
    throw std::invalid_argument("cpu_mesh_stages: the scene's resources hold no field mesh");
  }
  MeshStages out;
  out.plan = make_frame_plan(scene, resources.terrain_values(), resources.sketch_or_null());
  const FramePlan& plan = out.plan;
  const SurfaceParams<float> surface = make_terrain_params<float>(plan).surface;
  const geomipmap::Selection selection =
      geomipmap::select_levels(field->map, frame_mesh_view(scene, plan, skips.occluded_tiles));
  out.mesh = geomipmap::stitched_mesh(field->map, selection);
  out.grid = GridBuffers<float>(mesh_layout(out.mesh.vertex_column.size()));
  const IndexRange all{0, out.grid.valid.size()};
  const double above_base = plan.camera.position.y - scene.terrain.base_height;  // in double
  mesh_domain<float>(*field, out.mesh, plan.camera.position, all, out.grid.domain());
  mesh_heights<float>(*field, out.mesh, above_base, all, out.grid.height);
  mesh_surface<float>(*field, *resources.sketch_or_null(), out.mesh, surface.water_level,
                      surface.water_enabled != 0, all, out.grid.height, out.grid.surface());
  return out;
}

}  // namespace relief
