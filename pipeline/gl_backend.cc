#include "pipeline/gl_backend.h"

#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "core/frame_plan.h"
#include "core/input_file.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "pipeline/frame_skips.h"
#include "pipeline/memory_budget.h"
#include "pipeline/stage_table.h"
#include "raster/topology.h"

#ifdef RELIEF_WITH_GL
#include "gpu/gl_buffers.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_shading.h"
#include "gpu/gl_terrain.h"
#include "gpu/headless_gl.h"
#endif

namespace relief {

#ifdef RELIEF_WITH_GL
namespace {

// The process's GL context and the programs it compiled (llvmpipe takes a second or more to
// compile them: once per process, not per frame). `mutex` serialises GL frames.
struct GlSession {
  std::mutex mutex;
  std::unique_ptr<gpu::HeadlessGl> gl;
  std::string error;  // why there is no context
  std::unique_ptr<gpu::GlTerrainDraw> draw;
};

// The address space a GL driver maps beyond the frame's own memory (current_context).
constexpr std::uintmax_t kGlDriverAddressSpace = std::uintmax_t{768} << 20;

GlSession& session() {
  static GlSession* const state = new GlSession;  // never destroyed: the driver outlives it
  return *state;
}

// The context, current on this thread, or GlBackendError. Called with the session locked.
gpu::HeadlessGl& current_context(GlSession& s) {
  if (s.gl == nullptr && s.error.empty()) {
    // Under an address-space limit (ulimit -v) Mesa's llvmpipe crashes (SIGSEGV in its shader
    // compiler) instead of failing: refuse before the driver loads. Measured on llvmpipe (Mesa
    // 22.3, 2 cores): a small GL render dies with 691 MiB of address space left at this point
    // and succeeds with 730 MiB; kGlDriverAddressSpace, and 8 MiB for each rasteriser thread's
    // stack of a larger machine.
    const std::uintmax_t need =
        kGlDriverAddressSpace + (std::uintmax_t{8} << 20) * std::thread::hardware_concurrency();
    if (const std::optional<std::uintmax_t> left = address_space_remaining();
        left && *left < need) {
      throw GlBackendError("the address-space limit (ulimit -v) leaves " + format_bytes(*left) +
                           "; the GL driver needs about " + format_bytes(need) +
                           " of address space for its shader compiler and threads. Raise "
                           "ulimit -v or use a CPU backend (--backend simd)");
    }
    s.gl = gpu::HeadlessGl::open(s.error);  // current on this thread when it opens
    if (s.gl == nullptr && s.error.empty()) {
      s.error = "no OpenGL context";
    }
  }
  if (s.gl == nullptr) {
    throw GlBackendError("the GL backend needs OpenGL 4.5 through EGL: " + s.error);
  }
  if (!s.gl->make_current()) {
    throw GlBackendError("the GL context cannot be made current on this thread");
  }
  return *s.gl;
}

// Runs `work` with the context current on this thread, released afterwards; gpu/'s errors
// (GlError, a shader log, a limit the frame needs) become GlBackendError.
template <class Work>
void with_context(GlSession& s, const char* what, Work&& work) {
  gpu::HeadlessGl& gl = current_context(s);
  try {
    work();
  } catch (const std::exception& e) {
    gl.release();
    throw GlBackendError(std::string("the GL backend's ") + what + ": " + e.what());
  }
  gl.release();
}

class GlBackend final : public FrameBackend {
 public:
  GlBackend(const Scene& scene, const SceneResources& resources, const FrameRequest& request)
      : lock_(session().mutex),
        scene_(scene),
        resources_(resources),
        request_(request),
        plan_(make_frame_plan(scene, resources.terrain_values(), resources.sketch_or_null())),
        params_(make_terrain_params<float>(plan_)) {
    // Cast shadows have no GLSL twin yet (stage_table.h, kGlHasNoShadows): refused rather than
    // drawn without them, which a cross-check would report as the GL side's error.
    if (scene.lighting.shadows) {
      throw GlBackendError(
          "lighting.shadows = true: the GL backend has no cast shadows yet; allowed false with "
          "--backend gl (or render with --backend simd, reference or reference-double)");
    }
    with_context(session(), "set-up", [&] {
      terrain_ = std::make_unique<gpu::GlTerrain>(plan_.layout, resources_.terrain_values(),
                                                  resources_.sketch_or_null());
    });
  }

  // The frame's GL objects belong to the session's context: deleted there (GL deletes a name
  // in whatever context is current, so with another context current, a caller's own, it
  // would delete that context's objects of the same names, and with none it would abort).
  ~GlBackend() override {
    GlSession& s = session();
    if (s.gl != nullptr && s.gl->make_current()) {
      upload_.reset();
      terrain_.reset();
      s.gl->release();
    }
  }
  GlBackend(const GlBackend&) = delete;
  GlBackend& operator=(const GlBackend&) = delete;

  std::size_t units(StageId id) const override {
    switch (id) {
      case StageId::kProjectedDomain:
      case StageId::kFractal:
      case StageId::kSurface:
        return params_.domain.terrain_visible != 0 ? 1 : 0;
      case StageId::kTiles:
        return 1;
      default:
        return 0;  // culling and the software rasteriser's stages: not on the GL side
    }
  }

  void run(StageId id, std::size_t /*begin*/, std::size_t /*end*/) override {
    GlSession& s = session();
    switch (id) {
      case StageId::kProjectedDomain:
        with_context(s, "projected domain", [&] {
          terrain_->project_domain(params_.domain, params_.domain_rows, params_.planet);
        });
        return;
      case StageId::kFractal:
        with_context(s, "fractal", [&] {
          terrain_->evaluate_fbm(params_.fbm);
          terrain_->add_sketch(params_.sketch);     // §3's low-frequency base (none: no pass)
          terrain_->bend_vertices(params_.planet);  // a planet's bend (none: no pass)
        });
        return;
      case StageId::kSurface:
        with_context(s, "surface pass", [&] {
          terrain_->surface_pass(params_.surface);
          terrain_->bend_normals(params_.planet);  // into the bent frame (none: no pass)
        });
        return;
      case StageId::kTiles:
        with_context(s, "draw", [&] { draw(s); });
        return;
      default:
        return;
    }
  }

  void describe(StageId id, StageTime& time) const override {
    if (id == StageId::kTiles && time.ran) {
      time.name = "GL draw, stages 5-9";
    }
  }

  void finish(Frame& frame) override {
    frame.image = std::move(image_);
    // GL draws the grid's two triangles per cell (raster/topology.h); its rasteriser has no
    // set-up pieces or bins to count (the report says so rather than printing 0).
    frame.stats.raster.triangles = raster::GridTriangles{plan_.layout, {}, {}}.count();
  }

 private:
  void draw(GlSession& s) {
    const ShadingPlan shading = make_shading_plan(scene_, plan_, resources_.lattice.size);
    ShadeParams<float> shade = make_shade_params<float>(shading);
    add_planet_shading(plan_, scene_.terrain.base_height, shade);  // nothing on the plane
    // No culling on the GL side, hence no lowest drawn height: the water pass over terrain
    // runs wherever there is water (it changes no pixel above the water).
    apply_skips(request_.skips, true, shade);
    if (s.draw == nullptr) {
      s.draw = std::make_unique<gpu::GlTerrainDraw>();
    }
    gpu::GlGridStreams streams;
    streams.layout = plan_.layout;
    if (params_.domain.terrain_visible != 0) {
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
      streams.nu = request_.outputs.octaves ? name(gpu::GlStream::kNu) : 0;
      streams.valid = name(gpu::GlStream::kValid);
    } else {
      // Nothing to draw: an upload of the (zero, invalid) buffers keeps the draw's inputs
      // well-formed; only the background is drawn.
      empty_grid_ = std::make_unique<GridBuffers<float>>(plan_.layout);
      upload_ = std::make_unique<gpu::GlGridUpload>(*empty_grid_);
      streams = upload_->streams();
    }
    const gpu::GlShadeResources textures(ShadeResources{&resources_.lattice, resources_.textures});
    gpu::GlFrameImage gl =
        s.draw->draw(streams, params_.transform, shade, textures, plan_.camera.position.y);
    const FrameOutputs& o = request_.outputs;
    image_.width = gl.width;
    image_.height = gl.height;
    image_.srgb = std::move(gl.srgb);
    if (o.linear)
      image_.linear = std::move(gl.linear);
    if (o.depth)
      image_.depth = std::move(gl.depth);
    if (o.primitive)
      image_.primitive = std::move(gl.primitive);
    if (o.normal)
      image_.normal = std::move(gl.normal);
    if (o.world_height)
      image_.world_height = std::move(gl.world_height);
    if (o.octaves)
      image_.octaves = std::move(gl.octaves);
  }

  std::unique_lock<std::mutex> lock_;
  const Scene& scene_;
  const SceneResources& resources_;
  FrameRequest request_;
  FramePlan plan_;
  TerrainParams<float> params_;
  std::unique_ptr<gpu::GlTerrain> terrain_;
  std::unique_ptr<GridBuffers<float>> empty_grid_;
  std::unique_ptr<gpu::GlGridUpload> upload_;
  FrameImage image_;
};

}  // namespace

bool gl_backend_built() {
  return true;
}

std::string gl_renderer() {
  GlSession& s = session();
  const std::lock_guard<std::mutex> lock(s.mutex);
  gpu::HeadlessGl& gl = current_context(s);
  const std::string text = gl.renderer() + " (OpenGL " + gl.version() + ", " + gl.platform() + ")";
  gl.release();
  return text;
}

std::unique_ptr<FrameBackend> make_gl_backend(const Scene& scene, const SceneResources& resources,
                                              const FrameRequest& request) {
  return std::make_unique<GlBackend>(scene, resources, request);
}

GridBuffers<float> gl_terrain_stages(const Scene& scene, const NoiseLattice& lattice,
                                     const HeightSketch* sketch) {
  GlSession& s = session();
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
  with_context(s, "terrain stages", [&] {
    gpu::GlTerrain terrain(plan.layout, lattice, sketch);
    terrain.run(params);
    terrain.read_all(grid);
  });
  return grid;
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

#endif

}  // namespace relief
