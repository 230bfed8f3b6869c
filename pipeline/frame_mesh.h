// What a frame of terrain.heightfield.geomipmap draws, chosen on the CPU for every backend
// (core/heightfield/geomipmap.h): the view the tiles are selected for, the stitched mesh of
// the drawn tiles, its size and its counters. The CPU backends and the GL backend call the same
// functions, so both draw the same mesh with the same triangle numbers (de Boer's
// GeoMipMapping and Scape choose the levels on the CPU and draw index lists on the GPU).
#pragma once

#include <cstdint>

#include "core/frame_plan.h"
#include "core/heightfield/field_mesh.h"
#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"

namespace relief {

// The frame's view for select_levels: the camera at its height above terrain.base_height (the
// lattice's frame, field_mesh.h), the viewport, tau; occlusion culling where the scene asks for
// it and `occluded_tiles_skip` (FrameSkips::occluded_tiles) lets it run.
geomipmap::View frame_mesh_view(const Scene& scene, const FramePlan& plan,
                                bool occluded_tiles_skip);

// The most vertices and triangles the stitched mesh of `selection` can have: (T / 2^L + 1)^2
// vertices and 2 (T / 2^L)^2 triangles per drawn tile at level L.
struct MeshSize {
  std::uintmax_t vertices = 0, triangles = 0;
};
MeshSize mesh_size_bound(const FieldMesh& field, const geomipmap::Selection& selection);

// The stage-2 counters of a mesh frame (--stats): the tiles, the quadtree's and the occlusion
// buffer's work, the tiles drawn per level and the mesh's vertices.
void add_mesh_counters(const FieldMesh& field, const geomipmap::SelectionCounts& counts,
                       std::uint64_t vertices, StageTime& time);

// Stages 2-4 of the mesh a frame of `scene` draws (skips as `skips`), on the CPU in float (the
// portable loops every CPU backend runs): the mesh and its vertices' streams in the frame's
// layout (mesh_layout), and the frame's plan they were made from. What relief crosscheck compares
// the GL side's with.
struct MeshStages {
  FramePlan plan;
  geomipmap::Mesh mesh;
  GridBuffers<float> grid{GridLayout{}};
};
MeshStages cpu_mesh_stages(const Scene& scene, const SceneResources& resources,
                           const FrameSkips& skips = {});

}  // namespace relief
