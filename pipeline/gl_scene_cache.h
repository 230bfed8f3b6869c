// The GL backend's process-wide state (gl_backend.h): one headless context, and what its frames
// keep between them so that a frame uploads and compiles nothing it already has:
//
// - the terrain programs and the draw's, compiled once per process;
// - the terrain stages' streams (gpu::GlTerrain), kept while the grid's layout is the same;
// - the scene's uploads, kept while the SceneResources are the same: stage 3's lattice (or
//   basis grid) and the sketch in the GlTerrain, the shading's lattice and the proto-textures'
//   mip chains in a gpu::GlShadeResources;
// - the draw's index buffer and render targets, kept while their sizes are (gl_shading.h);
// - the timer queries of the passes.
//
// "The same SceneResources" is the same ResourceSerial (scene_resources.h): every object has
// its own, a copy a new one, a move hands it on; never the address alone, which a freed and a
// new SceneResources may share. As a guard against arrays reallocated (assigned, resized)
// without SceneResources::contents_changed(), the key also holds the sizes and addresses of
// the arrays uploaded: any difference uploads again. Values written into the same arrays are
// not seen without contents_changed(). Hashing the contents instead would read every texel
// each frame: 0.17 ms for the default scene's 5.25 MiB (lattice and five 256² mip chains; a
// four-lane multiply-xor hash, warm caches, one core of an AMD EPYC), 1.3 GiB and tens of ms
// with five 4096² textures; the serial costs nothing whatever the scene.
//
// Only compiled with RELIEF_WITH_GL. Every function needs the session's mutex held and its
// context current on the calling thread.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/grid_buffers.h"
#include "gpu/gl_buffers.h"
#include "gpu/gl_pass_timer.h"
#include "gpu/gl_shading.h"
#include "gpu/gl_terrain.h"
#include "gpu/headless_gl.h"
#include "pipeline/scene_resources.h"

namespace relief {

// What names an upload of part of a SceneResources: its serial, then the sizes and addresses of
// the arrays uploaded (the guard above).
struct GlResourceKey {
  std::uint64_t serial = 0;  // 0: nothing uploaded
  std::vector<std::uintptr_t> shape;

  bool operator==(const GlResourceKey&) const = default;
};

// Stage 3's part (terrain_values() and the sketch) and the shading's (the lattice and the
// proto-textures).
GlResourceKey terrain_resource_key(const SceneResources& resources);
GlResourceKey shading_resource_key(const SceneResources& resources);

class GlSceneCache {
 public:
  // The terrain stages of a grid of `layout` holding `resources`' stage-3 grid and sketch: the
  // kept one where both match, its lattice and sketch uploaded again where only the layout
  // does, a new one (the old one's streams freed first) otherwise. Its GL errors are the
  // caller's to check (gpu::GlErrorChecks::kByCaller) and its passes timed by pass_timer().
  gpu::GlTerrain& terrain(GridLayout layout, const SceneResources& resources);
  // The layout of the kept terrain stages' streams; none when there are none.
  std::optional<GridLayout> terrain_layout() const {
    return terrain_ != nullptr ? std::optional<GridLayout>(terrain_->layout()) : std::nullopt;
  }
  // The shading's lattice and proto-textures of `resources`, uploaded where they are not kept.
  const gpu::GlShadeResources& shading(const SceneResources& resources);
  gpu::GlTerrainDraw& draw();
  gpu::GlPassTimer& pass_timer();
  // The terrain programs alone (gl_terrain_stages builds its own GlTerrain with them).
  std::shared_ptr<const gpu::GlTerrainPrograms> terrain_programs();

  // Drops the streams and the scene's uploads (kept: the programs, the draw, the timer): after
  // a GL error, whose objects may be left half-written, and for tests that want the state of
  // a process's first frame.
  void forget_scene();

 private:
  std::shared_ptr<const gpu::GlTerrainPrograms> programs_;
  std::unique_ptr<gpu::GlTerrain> terrain_;
  GlResourceKey terrain_key_;
  std::unique_ptr<gpu::GlShadeResources> shading_;
  GlResourceKey shading_key_;
  std::unique_ptr<gpu::GlTerrainDraw> draw_;
  std::unique_ptr<gpu::GlPassTimer> timer_;
};

// The process's context and cache. `mutex` serialises GL frames (and every other use of the
// context); never destroyed (the driver outlives it).
struct GlSession {
  std::mutex mutex;
  std::unique_ptr<gpu::HeadlessGl> gl;
  std::string error;  // why there is no context
  GlSceneCache cache;
};

GlSession& gl_session();

// Keeps the session's context current on the constructing thread until destroyed (then what
// was current there before is current again). Throws GlBackendError (gl_backend.h) when there
// is no context, refusing before the driver loads under an address-space limit it cannot live
// with. Made with the session's mutex held.
class GlCurrent {
 public:
  explicit GlCurrent(GlSession& session);
  ~GlCurrent();
  GlCurrent(const GlCurrent&) = delete;
  GlCurrent& operator=(const GlCurrent&) = delete;

  gpu::HeadlessGl& gl() const { return *gl_; }

 private:
  gpu::HeadlessGl* gl_ = nullptr;
};

}  // namespace relief
