#include "pipeline/gl_backend.h"

#include <cstdint>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "core/frame_plan.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "pipeline/frame_mesh.h"
#include "pipeline/frame_skips.h"
#include "pipeline/memory_budget.h"
#include "pipeline/parallel_rows.h"
#include "pipeline/stage_table.h"
#include "raster/topology.h"

#ifdef RELIEF_WITH_GL
#include "gpu/gl_buffers.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_shading.h"
#include "gpu/gl_terrain.h"
#include "pipeline/gl_frame_mesh.h"
#include "pipeline/gl_scene_cache.h"
#endif

namespace relief {

#ifdef RELIEF_WITH_GL
namespace {

// Runs `work`, turning gpu/'s errors (GlError, a shader log, a limit the frame needs) into
// GlBackendError naming `what`. After a failure the scene's GL objects may be half-written:
// they are dropped, and the next frame makes them again.
template <class Work>
void guarded(GlSession& s, const char* what, Work&& work) {
  try {
    work();
  } catch (const GlBackendError&) {
    s.cache.forget_scene();
    throw;
  } catch (const MemoryLimitError&) {
    throw;  // refused before any GL work (a GeoMipMap mesh too large): the caller's exit
  } catch (const std::exception& e) {
    s.cache.forget_scene();
    throw GlBackendError(std::string("the GL backend's ") + what + ": " + e.what());
  }
}

// A frame's GL work, with no synchronisation inside the frame:
// - The context is made current once, by the constructor, on the thread that runs the frame,
//   and released by the destructor. Each stage's GL commands are issued in after(), which the
//   runner calls on that thread (frame.cc's run_table); run() has nothing to do in parallel
//   (one stream of GL commands), so no stage takes the context to another thread.
// - Nothing is uploaded or compiled that an earlier frame left in the session's cache
//   (gl_scene_cache.h); the parameter structs alone are uploaded each frame.
// - glGetError is read once per stage (GlErrorChecks::kByCaller), and twice by the draw. An
//   error is recorded when the call is made, so glGetError never waits for the GPU; under a
//   threaded driver (NVIDIA's threaded optimisation, off by default on Linux; Mesa's glthread)
//   it waits for the driver's thread to catch up with the calls, a few per frame.
// - The one wait is the read-back of the requested outputs, after which the passes' timer
//   queries are read (they are complete by then).
class GlBackend final : public FrameBackend {
 public:
  GlBackend(const Scene& scene, const SceneResources& resources, const FrameRequest& request)
      : lock_(gl_session().mutex),
        scene_(scene),
        resources_(resources),
        request_(request),
        plan_(make_frame_plan(scene, resources.terrain_values(), resources.sketch_or_null(),
                              thread_pool_rows())),
        params_(make_terrain_params<float>(plan_)) {
    if (const std::string missing = gl_missing_feature(scene); !missing.empty()) {
      throw GlBackendError(missing);
    }
    GlSession& s = gl_session();
    current_.emplace(s);
    guarded(s, "set-up", [&] {
      gpu::clear_gl_errors();
      timer_ = &s.cache.pass_timer();
      timer_->clear();  // a failed frame's passes
      if (mesh_mode()) {
        if (resources_.field_mesh_or_null() == nullptr) {
          throw GlBackendError(
              "terrain.heightfield.geomipmap is set; the scene's resources hold no field mesh");
        }
        return;  // the mesh's streams: stage 2 (GlFrameMesh::run)
      }
      if (params_.domain.terrain_visible != 0) {
        terrain_ = &s.cache.terrain(plan_.layout, resources_);
      }
    });
  }

  // The frame's own GL objects (upload_) go before current_ releases the context: GL deletes
  // a name in whatever context is current, so with a caller's own context current it would
  // delete that context's object of the same name, and with none libepoxy aborts.
  ~GlBackend() override = default;
  GlBackend(const GlBackend&) = delete;
  GlBackend& operator=(const GlBackend&) = delete;

  std::size_t units(StageId id) const override {
    switch (id) {
      case StageId::kProjectedDomain:
      case StageId::kFractal:
      case StageId::kSurface:
        return terrain_ != nullptr || mesh_mode() ? 1 : 0;
      case StageId::kTiles:
        return 1;
      default:
        return 0;  // culling and the software rasteriser's stages: not on the GL side
    }
  }

  // Nothing in parallel: the stage's GL commands are issued by after() (above).
  void run(StageId /*id*/, std::size_t /*begin*/, std::size_t /*end*/) override {}

  void after(StageId id) override {
    if (units(id) == 0) {
      return;
    }
    GlSession& s = gl_session();
    if (mesh_mode() && id <= StageId::kSurface) {
      guarded(s, "GeoMipMap mesh", [&] {
        terrain_ = mesh_.run(s.cache, id, scene_, resources_, plan_, request_, params_.surface);
      });
      return;
    }
    switch (id) {
      case StageId::kProjectedDomain:
        guarded(s, "projected domain", [&] {
          terrain_->project_domain(params_.domain, params_.domain_rows, params_.planet);
          gpu::check_gl("stage 2 (domain.comp)");
        });
        return;
      case StageId::kFractal:
        guarded(s, "fractal", [&] {
          terrain_->evaluate_fbm(params_.fbm);
          terrain_->add_sketch(params_.sketch);     // §3's low-frequency base (none: no pass)
          terrain_->bend_vertices(params_.planet);  // a planet's bend (none: no pass)
          gpu::check_gl("stage 3 (reach.comp, forms.comp, fbm.comp, sketch.comp, bend.comp)");
        });
        return;
      case StageId::kSurface:
        guarded(s, "surface pass", [&] {
          terrain_->surface_pass(params_.surface);
          terrain_->bend_normals(params_.planet);  // into the bent frame (none: no pass)
          gpu::check_gl("stage 4 (surface.comp, bend_normals.comp)");
        });
        return;
      case StageId::kTiles:
        guarded(s, "draw", [&] { draw(s); });
        return;
      default:
        return;
    }
  }

  void describe(StageId id, StageTime& time) const override {
    if (id == StageId::kTiles && time.ran) {
      time.name = "GL draw, stages 5-9";
    }
    if (id == StageId::kProjectedDomain && mesh_mode() && time.ran) {
      add_mesh_counters(*resources_.field_mesh, mesh_.counts(),
                        std::uint64_t(mesh_.mesh().vertex_column.size()), time);
    }
  }

  void finish(Frame& frame) override {
    frame.image = std::move(image_);
    if (mesh_mode()) {  // the mesh's stable triangle numbers, as the CPU backends give them
      geomipmap::stable_primitive_ids(mesh_.mesh(), frame.image.primitive);
    }
    frame.stats.gpu_passes = std::move(passes_);
    // GL draws the grid's two triangles per cell (raster/topology.h), or the mesh's index list;
    // its rasteriser has no set-up pieces or bins to count (the report says so rather than
    // printing 0).
    frame.stats.raster.triangles = mesh_mode()
                                       ? std::uint32_t(mesh_.mesh().indices.size() / 3)
                                       : raster::GridTriangles{plan_.layout, {}, {}}.count();
  }

 private:
  bool mesh_mode() const {
    return scene_.terrain.heightfield && scene_.terrain.heightfield->geomipmap;
  }

  void draw(GlSession& s) {
    const ShadingPlan shading = make_shading_plan(scene_, plan_, resources_.lattice.size);
    ShadeParams<float> shade = make_shade_params<float>(shading);
    add_planet_shading(plan_, scene_.terrain.base_height, shade);  // nothing on the plane
    // No culling on the GL side, hence no lowest drawn height: the water pass over terrain
    // runs wherever there is water (it changes no pixel above the water).
    apply_skips(request_.skips, true, shade);
    const FrameOutputs& o = request_.outputs;
    gpu::GlGridStreams streams;
    streams.layout = terrain_ != nullptr ? terrain_->layout() : plan_.layout;
    if (terrain_ != nullptr) {
      const auto name = [&](gpu::GlStream stream) { return terrain_->buffer(stream); };
      // On a planet the bent positions (docs/planet.md): stage 5 transforms them, stage 8
      // reads the bent x and z, the unbent height and the drop.
      const bool planet = params_.planet.enabled != 0;
      streams.dx = name(planet ? gpu::GlStream::kBentX : gpu::GlStream::kDx);
      streams.dz = name(planet ? gpu::GlStream::kBentZ : gpu::GlStream::kDz);
      streams.position_y = planet ? name(gpu::GlStream::kBentY) : 0;
      streams.drop = planet ? name(gpu::GlStream::kBentDrop) : 0;
      streams.height_origin = planet ? static_cast<float>(-plan_.planet.altitude) : 0.0f;
      streams.height = name(gpu::GlStream::kHeight);
      streams.nx = name(gpu::GlStream::kNx);
      streams.ny = name(gpu::GlStream::kNy);
      streams.nz = name(gpu::GlStream::kNz);
      streams.slope = name(gpu::GlStream::kSlope);
      streams.water_depth = name(gpu::GlStream::kWaterDepth);
      streams.nu = o.octaves ? name(gpu::GlStream::kNu) : 0;
      streams.valid = name(gpu::GlStream::kValid);
    } else {
      // Nothing to draw: an upload of the (zero, invalid) buffers keeps the draw's inputs
      // well-formed; only the background is drawn.
      empty_grid_ = std::make_unique<GridBuffers<float>>(plan_.layout);
      upload_ = std::make_unique<gpu::GlGridUpload>(*empty_grid_);
      streams = upload_->streams();
    }
    gpu::GlDrawOptions options;
    options.readback = {o.linear, o.depth, o.primitive, o.normal, o.world_height, o.octaves};
    options.timer = timer_;
    options.indexed = mesh_mode();
    options.indices = mesh_.mesh().indices;  // the mesh's (none drawn where every tile was culled)
    // Gradient shading lights the vertices in the vertex shader (terrain.vert, stage 5).
    TransformParams<float> transform = params_.transform;
    add_gouraud_lighting(shading, transform);
    gpu::GlFrameImage gl = s.cache.draw().draw(
        streams, transform, shade, s.cache.shading(resources_), plan_.camera.position.y, options);
    for (gpu::GlPassTime& pass : timer_->collect()) {
      passes_.push_back({std::move(pass.name), pass.ms, true, {}});
    }
    passes_.push_back({"read-back (CPU wall time)", gl.readback_ms, true, {}});
    image_.width = gl.width;
    image_.height = gl.height;
    image_.srgb = std::move(gl.srgb);
    image_.linear = std::move(gl.linear);  // each empty unless requested (GlReadback)
    image_.depth = std::move(gl.depth);
    image_.primitive = std::move(gl.primitive);
    image_.normal = std::move(gl.normal);
    image_.world_height = std::move(gl.world_height);
    image_.octaves = std::move(gl.octaves);
    // What the session keeps for the next frame lies outside every later frame's memory
    // estimate (job_memory.h), a CPU frame's included, and under llvmpipe it is host memory: a
    // large frame's targets (52 bytes a pixel, the staging 4 more) and grid (the streams' 44
    // bytes a vertex, the indices' 24 a cell) are freed when it ends, so that at most
    // kKeptFrameBytes of each stays between frames.
    const std::uintmax_t pixels = std::uintmax_t(gl.width) * std::uintmax_t(gl.height);
    if (pixels * 56 > kKeptFrameBytes || options.indices.size_bytes() > kKeptFrameBytes) {
      s.cache.draw().release_frame_objects();  // a GeoMipMap mesh's index buffer too
    }
    if (std::uintmax_t(streams.layout.size()) * (44 + 24) > kKeptFrameBytes) {
      s.cache.forget_scene();
    }
  }

  // The most each of a frame's targets and grid the session keeps after it (draw).
  static constexpr std::uintmax_t kKeptFrameBytes = std::uintmax_t{256} << 20;

  std::unique_lock<std::mutex> lock_;
  std::optional<GlCurrent> current_;  // after the lock, before every GL object of the frame
  const Scene& scene_;
  const SceneResources& resources_;
  FrameRequest request_;
  FramePlan plan_;
  TerrainParams<float> params_;
  gpu::GlTerrain* terrain_ = nullptr;  // the session's; null when no terrain is visible
  gpu::GlPassTimer* timer_ = nullptr;  // the session's
  std::unique_ptr<GridBuffers<float>> empty_grid_;
  std::unique_ptr<gpu::GlGridUpload> upload_;
  FrameImage image_;
  std::vector<StageTime> passes_;
  GlFrameMesh mesh_;  // a GeoMipMap frame's (terrain.heightfield.geomipmap)
};

}  // namespace

bool gl_backend_built() {
  return true;
}

std::string gl_renderer() {
  GlSession& s = gl_session();
  const std::lock_guard<std::mutex> lock(s.mutex);
  const GlCurrent current(s);
  return current.gl().renderer() + " (OpenGL " + current.gl().version() + ", " +
         current.gl().platform() + ")";
}

std::unique_ptr<FrameBackend> make_gl_backend(const Scene& scene, const SceneResources& resources,
                                              const FrameRequest& request) {
  return std::make_unique<GlBackend>(scene, resources, request);
}

GridBuffers<float> gl_terrain_stages(const Scene& scene, const NoiseLattice& lattice,
                                     const HeightSketch* sketch) {
  GlSession& s = gl_session();
  const std::lock_guard<std::mutex> lock(s.mutex);
  const FramePlan plan = make_frame_plan(scene, lattice, sketch);
  const TerrainParams<float> params = make_terrain_params<float>(plan);
  GridBuffers<float> grid(plan.layout);
  if (params.planet.enabled != 0) {
    grid.allocate_bent();  // the bend's outputs (docs/planet.md)
  }
  if (params.domain.terrain_visible == 0) {
    return grid;
  }
  const GlCurrent current(s);
  guarded(s, "terrain stages", [&] {
    // Its own streams (read back at once), the session's programs.
    gpu::GlTerrain terrain(s.cache.terrain_programs(), plan.layout, lattice, sketch);
    terrain.run(params);
    terrain.read_all(grid);
  });
  return grid;
}

void forget_gl_scene() {
  GlSession& s = gl_session();
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (s.gl == nullptr) {
    return;  // nothing was made
  }
  const GlCurrent current(s);
  s.cache.forget_scene();
}

#else

bool gl_backend_built() {
  return false;
}

std::string gl_renderer() {
  throw GlBackendError("this build of Relief has no GL side (configured with RELIEF_WITH_GL=OFF)");
}

std::unique_ptr<FrameBackend> make_gl_backend(const Scene&, const SceneResources&,
                                              const FrameRequest&) {
  throw GlBackendError("this build of Relief has no GL side (configured with RELIEF_WITH_GL=OFF)");
}

GridBuffers<float> gl_terrain_stages(const Scene&, const NoiseLattice&, const HeightSketch*) {
  throw GlBackendError("this build of Relief has no GL side (configured with RELIEF_WITH_GL=OFF)");
}

GridBuffers<float> gl_mesh_stages(const Scene&, const SceneResources&, const FrameSkips&) {
  throw GlBackendError("this build of Relief has no GL side (configured with RELIEF_WITH_GL=OFF)");
}

void forget_gl_scene() {}

#endif

std::string gl_missing_feature(const Scene& scene) {
  const std::string other =
      " with --backend gl (or render with --backend simd, reference or reference-double)";
  // Refused rather than drawn without, which a cross-check would report as the GL side's error.
  if (scene.lighting.shadows) {  // stage_table.h, kGlHasNoShadows
    return "lighting.shadows = true: the GL backend has no cast shadows yet; allowed false" + other;
  }
  if (scene.lighting.sky_occlusion) {  // the same cache
    return "lighting.sky_occlusion = true: the GL backend has no sky light yet; allowed false" +
           other;
  }
  if (scene.water.reflect_terrain && scene.terrain.water_level) {  // the same cache
    return "water.reflect_terrain = true: the GL backend has no terrain reflections yet; allowed "
           "false" +
           other;
  }
  return {};
}

}  // namespace relief
