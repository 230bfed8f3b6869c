// What a scene needs before its first frame, built once: the noise lattice and the
// proto-texture of every material layer (built-in textures synthesised, PNG files loaded and
// checked), each with the variance-reduced mip chain of §4.2.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/height_sketch.h"
#include "core/heightfield/field_mesh.h"
#include "core/lattice.h"
#include "core/proto_texture.h"
#include "core/scene/scene.h"
#include "core/shade.h"
#include "core/skybox.h"
#include "pipeline/basis_resources.h"

namespace relief {

// A process-unique number for the contents of one SceneResources, so that what is built from
// them (the GL backend's uploads, pipeline/gl_scene_cache.h) can be kept between frames and
// found again: an address cannot name contents, since a SceneResources freed and another
// allocated may share it. Every new object draws a new number from an atomic counter (never 0,
// never reused); a copy draws its own too, since either may then be changed apart from the
// other; a move hands the number on with the contents, and the object moved from, whose
// contents are gone, draws a new one.
class ResourceSerial {
 public:
  ResourceSerial() : value_(next()) {}
  ResourceSerial(const ResourceSerial&) : value_(next()) {}
  ResourceSerial& operator=(const ResourceSerial&) {
    value_ = next();
    return *this;
  }
  ResourceSerial(ResourceSerial&& other) noexcept : value_(other.value_) { other.value_ = next(); }
  ResourceSerial& operator=(ResourceSerial&& other) noexcept {
    value_ = other.value_;
    other.value_ = next();
    return *this;
  }
  ~ResourceSerial() = default;

  std::uint64_t value() const { return value_; }
  void renew() { value_ = next(); }

 private:
  static std::uint64_t next() noexcept;
  std::uint64_t value_;
};

// Once a frame has used a SceneResources, its contents are treated as fixed: to change them,
// make another object (load_scene_resources), or call contents_changed() after changing
// them in place, which gives them a new serial. Nothing in Relief changes them after loading.
struct SceneResources {
  NoiseLattice lattice;
  std::vector<ProtoTexture> textures;  // one per scene.shading.layers entry
  // terrain.sketch's or terrain.heightfield's texels, when the scene has one
  std::optional<HeightSketch> sketch;
  // terrain.heightfield.geomipmap's lattice and tiles (core/heightfield/field_mesh.h), when set.
  std::optional<FieldMesh> field_mesh;
  // terrain.basis's composed grid (§3 Eq. 2, core/basis_images.h), when the scene has one: it
  // replaces `lattice` in stage 3 alone; the shading's noise keeps the lattice.
  std::optional<NoiseLattice> basis;
  std::optional<Skybox> skybox;  // sky.skybox's faces (core/skybox.h), when the scene has one
  // What loading found worth saying that is no error (an image that does not tile, a field
  // basis mode ignores); the command line prints each once on stderr.
  std::vector<std::string> notes;
  ResourceSerial serial;  // names the contents above (ResourceSerial); copies get their own

  void contents_changed() { serial.renew(); }

  const HeightSketch* sketch_or_null() const { return sketch ? &*sketch : nullptr; }
  const NoiseLattice* basis_or_null() const { return basis ? &*basis : nullptr; }
  const Skybox* skybox_or_null() const { return skybox ? &*skybox : nullptr; }
  const FieldMesh* field_mesh_or_null() const { return field_mesh ? &*field_mesh : nullptr; }
  // What stage 8 samples.
  ShadeResources shading() const { return {&lattice, textures, skybox_or_null()}; }
  // Stage 3's grid: the basis grid, or the noise lattice.
  const NoiseLattice& terrain_values() const { return basis ? *basis : lattice; }
};

// Throws SceneError naming the layer for a texture file that cannot be read, is not a PNG, or
// is not square with a power-of-two side from 4 to 4096; and naming terrain.sketch.image for a
// sketch that cannot be read, is not a PNG, has more than one channel or a depth other than 8
// or 16 bits, or is not 2 to kMaxSketchSize texels on a side; and naming the terrain.basis
// field of a basis image refused by load_basis_grid (basis_resources.h).
SceneResources load_scene_resources(const Scene& scene);

// sky.skybox's faces (nullopt without one): each file checked as a layer's texture is
// (decode_texture_png) but at most kMaxSkyboxSize a side, all six of one size, else a
// SceneError naming the face (`sky.skybox.faces[3] = "down.png"`).
std::optional<Skybox> load_skybox(const Scene& scene);

// Whether load_scene_resources gives `a` and `b` the same resources: it reads their terrain and
// shading settings and sky.skybox's faces and intensity alone (the files they name are read again
// only by a new load). A caller that keeps resources across scene changes (the Python module's
// Scene.set) keeps them where this holds.
bool same_resource_inputs(const Scene& a, const Scene& b);

// terrain.sketch's or terrain.heightfield's texels (nullopt when the scene has neither), with
// load_scene_resources' checks.
std::optional<HeightSketch> load_height_sketch(const Scene& scene);

// The proto-texture image of one layer, linear RGB (PNG files are sRGB-decoded). A file's PNG
// header is checked before the rest of it is read; then decode_texture_png.
RgbImage load_layer_texture(const MaterialLayer& layer, int builtin_size, const std::string& path);

// A texture PNG already in memory, checked as load_layer_texture checks a file (signature,
// square power-of-two side from 4 to 4096, 8 bits per channel, at most
// limits::kMaxTextureFileBytes, every chunk within the file, image data that inflates to no
// more than the header's size: image/png_layout.h) and decoded to linear RGB. `field` names
// the texture in messages (`shading.layers[2].texture = "a.png"`), `path` is the SceneError's
// JSON path. Throws SceneError. The texture fuzzer (fuzz/fuzz_inputs.h) calls it.
RgbImage decode_texture_png(const std::vector<unsigned char>& png, const std::string& field,
                            const std::string& path);

}  // namespace relief
