// The GL backend (Backend::kGl): the frame's stage table run by the GLSL twins of the stages in
// gpu/ on a headless OpenGL 4.5 context, an NVIDIA GPU through the EGL device platform where
// there is one, Mesa's llvmpipe through the surfaceless platform elsewhere. Stages 1-4 are
// compute shaders writing the grid's streams into GL buffers (gpu/gl_terrain.h), which the
// draw of stages 5-9 reads without a round trip (gpu/gl_shading.h). The CPU computes the
// frame's plan and parameter structs, the same bytes the CPU backends read.
//
// What the GL backend does not do: the vertex culling of the height bounds and the heights
// (its stages do not run: the GPU evaluates every valid vertex and its clipper discards what
// lies outside the frustum, which changes no pixel), and the tiles of the software
// rasteriser (GL rasterises). docs/gl-backend.md says how far its frames are from the CPU's.
//
// One process-wide context serves every GL frame, one frame at a time; it is current on the
// thread that runs a frame from the frame's start to its end. What frames keep between them
// (programs, streams, the scene's uploads, render targets) and how a scene's resources are
// recognised: gl_scene_cache.h. A frame reads back only the outputs its request asks for, and
// reports each GPU pass's time from GL timer queries (FrameStats::gpu_passes).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "core/grid_buffers.h"
#include "pipeline/frame_backend.h"
#include "pipeline/scene_resources.h"

namespace relief {

// No GL context could be made, the GL lacks 4.5 or a limit the frame needs, a shader failed or
// a GL call reported an error: the message says which (relief exits 2).
class GlBackendError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Whether this build has the GL side (RELIEF_WITH_GL).
bool gl_backend_built();

// What of `scene` the GL backend has no twin of yet, as the refusal's message ("lighting.shadows
// = true: the GL backend has no cast shadows yet; allowed false ..."), or empty where it draws
// the whole scene. The GL backend refuses such a scene; relief stress and sweep skip its GL
// rows with this reason.
std::string gl_missing_feature(const Scene& scene);

// The GL context's description, "NVIDIA H100 80GB HBM3/PCIe/SSE2 (OpenGL 4.6.0 NVIDIA 580.x,
// EGL device)", opening the shared context if needed; throws GlBackendError when there is none.
std::string gl_renderer();

// The frame's backend (frame.cc): holds the GL session, its context current on the calling
// thread, until destroyed, on that thread; `resources` must outlive it.
std::unique_ptr<FrameBackend> make_gl_backend(const Scene& scene, const SceneResources& resources,
                                              const FrameRequest& request);

// Stages 1-4 on the GL side with every vertex evaluated (as relief stages and
// run_terrain_stages do on the CPU): the grid's buffers read back.
GridBuffers<float> gl_terrain_stages(const Scene& scene, const NoiseLattice& lattice,
                                     const HeightSketch* sketch = nullptr);

// Stages 2-4 of the GeoMipMap mesh a frame of `scene` draws (terrain.heightfield.geomipmap;
// skips as `skips`) on the GL side (gpu/shaders/mesh.comp), its streams read back in the GL's
// layout: rows of kMeshRowVertices, vertex k at k as in cpu_mesh_stages (pipeline/frame_mesh.h),
// a power of two of rows (the padding invalid). Throws GlBackendError as a frame does.
GridBuffers<float> gl_mesh_stages(const Scene& scene, const SceneResources& resources,
                                  const FrameSkips& skips = {});

// Drops what GL frames keep of the last scene (its uploads and the grid's streams; the compiled
// programs stay), so that the next frame starts as a process's first does. For tests; frames
// never need it (gl_scene_cache.h).
void forget_gl_scene();

}  // namespace relief
