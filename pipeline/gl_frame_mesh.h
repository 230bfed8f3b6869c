// The GL backend's GeoMipMapping (terrain.heightfield.geomipmap): stage 2 selects the tiles and
// stitches their mesh on the CPU as the CPU backends do (pipeline/frame_mesh.h), and the GPU
// computes the vertices' stages 2-4 (gpu/shaders/mesh.comp, gl_terrain.h) into streams of rows
// of kMeshRowVertices; the draw then reads the mesh's index list (GlDrawOptions::indices).
// Built only with the GL side (RELIEF_WITH_GL).
#pragma once

#include "core/frame_plan.h"
#include "core/heightfield/field_mesh.h"
#include "core/scene/scene.h"
#include "core/stage_params.h"
#include "gpu/gl_terrain.h"
#include "pipeline/frame.h"
#include "pipeline/frame_mesh.h"
#include "pipeline/gl_scene_cache.h"
#include "pipeline/scene_resources.h"

namespace relief {

class GlFrameMesh {
 public:
  // Stage `id` (2, 3 or 4) of the frame's mesh; the other stages have no mesh work. Stage 2
  // selects and stitches the mesh, refuses (MemoryLimitError) one whose host copies and GL
  // buffers could exceed request.max_bin_bytes, and takes the session's streams for it.
  // Returns the streams the frame draws: null where every tile was culled.
  gpu::GlTerrain* run(GlSceneCache& cache, StageId id, const Scene& scene,
                      const SceneResources& resources, const FramePlan& plan,
                      const FrameRequest& request, const SurfaceParams<float>& surface);

  const geomipmap::Mesh& mesh() const { return mesh_; }
  const geomipmap::SelectionCounts& counts() const { return counts_; }

 private:
  geomipmap::Mesh mesh_;
  geomipmap::SelectionCounts counts_;
  gpu::GlTerrain* terrain_ = nullptr;
};

}  // namespace relief
