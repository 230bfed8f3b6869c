#include "pipeline/gl_scene_cache.h"

#include <optional>
#include <thread>

#include "core/input_file.h"
#include "pipeline/gl_backend.h"
#include "pipeline/memory_budget.h"

namespace relief {

namespace {

// The address space a GL driver maps beyond the frame's own memory (GlCurrent).
constexpr std::uintmax_t kGlDriverAddressSpace = std::uintmax_t{768} << 20;

void add_array(GlResourceKey& key, const void* data, std::size_t size) {
  key.shape.push_back(reinterpret_cast<std::uintptr_t>(data));
  key.shape.push_back(size);
}

void add_lattice(GlResourceKey& key, const NoiseLattice& lattice) {
  key.shape.push_back(static_cast<std::uintptr_t>(lattice.size));
  add_array(key, lattice.values.data(), lattice.values.size());
}

}  // namespace

GlResourceKey terrain_resource_key(const SceneResources& resources) {
  GlResourceKey key{resources.serial.value(), {}};
  add_lattice(key, resources.terrain_values());
  const HeightSketch* sketch = resources.sketch_or_null();
  if (sketch != nullptr) {
    key.shape.push_back(static_cast<std::uintptr_t>(sketch->width));
    key.shape.push_back(static_cast<std::uintptr_t>(sketch->height));
    add_array(key, sketch->heights.data(), sketch->heights.size());
  }
  return key;
}

GlResourceKey shading_resource_key(const SceneResources& resources) {
  GlResourceKey key{resources.serial.value(), {}};
  add_lattice(key, resources.lattice);
  for (const ProtoTexture& texture : resources.textures) {
    add_array(key, texture.texels.data(), texture.texels.size());
    key.shape.push_back(texture.levels.size());
  }
  if (resources.skybox) {
    add_array(key, resources.skybox->texels.data(), resources.skybox->texels.size());
    key.shape.push_back(std::size_t(resources.skybox->size));
  } else {
    key.shape.push_back(0);  // no skybox: a shape no face size gives
  }
  return key;
}

std::shared_ptr<const gpu::GlTerrainPrograms> GlSceneCache::terrain_programs() {
  if (programs_ == nullptr) {
    programs_ = std::make_shared<const gpu::GlTerrainPrograms>(gpu::build_terrain_programs());
  }
  return programs_;
}

gpu::GlPassTimer& GlSceneCache::pass_timer() {
  if (timer_ == nullptr) {
    timer_ = std::make_unique<gpu::GlPassTimer>();
  }
  return *timer_;
}

gpu::GlTerrain& GlSceneCache::terrain(GridLayout layout, const SceneResources& resources) {
  GlResourceKey key = terrain_resource_key(resources);
  const bool same_layout = terrain_ != nullptr && terrain_->layout().width == layout.width &&
                           terrain_->layout().height == layout.height &&
                           terrain_->layout().pitch == layout.pitch;
  if (!same_layout) {
    terrain_.reset();  // its streams go before the new ones are allocated
    terrain_key_ = {};
    terrain_ = std::make_unique<gpu::GlTerrain>(
        terrain_programs(), layout, resources.terrain_values(), resources.sketch_or_null());
    terrain_->set_error_checks(gpu::GlErrorChecks::kByCaller);
    terrain_->set_pass_timer(&pass_timer());
    terrain_key_ = std::move(key);
  } else if (!(terrain_key_ == key)) {
    terrain_key_ = {};  // nothing valid until both uploads have succeeded
    terrain_->set_lattice(resources.terrain_values());
    terrain_->set_sketch(resources.sketch_or_null());
    terrain_key_ = std::move(key);
  }
  return *terrain_;
}

const gpu::GlShadeResources& GlSceneCache::shading(const SceneResources& resources) {
  GlResourceKey key = shading_resource_key(resources);
  if (shading_ == nullptr || !(shading_key_ == key)) {
    shading_.reset();
    shading_key_ = {};
    shading_ = std::make_unique<gpu::GlShadeResources>(resources.shading());
    shading_key_ = std::move(key);
  }
  return *shading_;
}

gpu::GlTerrainDraw& GlSceneCache::draw() {
  if (draw_ == nullptr) {
    draw_ = std::make_unique<gpu::GlTerrainDraw>();
  }
  return *draw_;
}

void GlSceneCache::forget_scene() {
  terrain_.reset();
  terrain_key_ = {};
  shading_.reset();
  shading_key_ = {};
}

GlSession& gl_session() {
  static GlSession* const state = new GlSession;  // never destroyed: the driver outlives it
  return *state;
}

GlCurrent::GlCurrent(GlSession& s) {
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
  gl_ = s.gl.get();
}

GlCurrent::~GlCurrent() {
  gl_->release();
}

}  // namespace relief
