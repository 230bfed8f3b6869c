// GL objects that gpu/'s terrain draw reads: the grid's structure-of-arrays streams
// (core/grid_buffers.h) as buffer objects, and the scene's resources of stage 8 (the noise
// lattice, the proto-textures with the CPU's mip chains). Requires a current context; every
// object is deleted with its owner.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/grid_buffers.h"
#include "core/shade.h"

namespace relief::gpu {

// Names of GL buffer objects holding the grid's streams, vertex (i, j) at element
// j * pitch + i, as core/grid_buffers.h lays them out: float streams 4 bytes per vertex,
// `valid` and `need` 1 byte per vertex (each buffer at least layout.size() elements, the byte
// streams rounded up to whole 4-byte words). Whoever wrote them (an upload, or the compute
// stages 1-4 on the GPU) keeps them; the draw only reads them.
struct GlGridStreams {
  GridLayout layout;
  // Camera-relative position (stages 2-3); on a planet dx and dz name the bent x and z, and
  // height stays the unbent one (materials and water are radial; docs/planet.md).
  std::uint32_t dx = 0, dz = 0, height = 0;
  // A planet's bent y (what stage 5 transforms; 0: height, the plane) and curvature drop
  // (what stage 8 subtracts; 0: none, the plane).
  std::uint32_t position_y = 0, drop = 0;
  // The camera-relative height the draw interpolates heights from (as offsets): a planet's
  // datum, -altitude, where heights are the camera's altitude in size; 0 on the plane.
  float height_origin = 0;
  std::uint32_t nx = 0, ny = 0, nz = 0;      // unit normal (stage 4)
  std::uint32_t slope = 0, water_depth = 0;  // stage 4
  std::uint32_t nu = 0;                      // octave count (stage 2); 0: no octaves output
  std::uint32_t valid = 0;                   // stage 2: a triangle needs its cell's 4 valid
  std::uint32_t need = 0;  // VertexNeed flags (core/vertex_culling.h); 0: every vertex kDraw
};

// CPU grid buffers uploaded into buffer objects (what the tests use); a grid with bent
// positions (a planet's, GridBuffers::allocate_bent) uploads them as its dx, dz, position_y and
// drop.
class GlGridUpload {
 public:
  // `need`: empty, or one VertexNeed byte per vertex (layout.size()).
  explicit GlGridUpload(const GridBuffers<float>& grid, std::span<const std::uint8_t> need = {});
  ~GlGridUpload();
  GlGridUpload(const GlGridUpload&) = delete;
  GlGridUpload& operator=(const GlGridUpload&) = delete;

  const GlGridStreams& streams() const { return streams_; }

 private:
  void upload(const GridBuffers<float>& grid, std::span<const std::uint8_t> need);

  GlGridStreams streams_;
  std::vector<std::uint32_t> owned_;
};

// The noise lattice (a storage buffer: P, P - 1, two pad words, then the values), one
// GL_RGB32F texture per material layer holding the CPU's mip chain level by level (§4.2's
// variance-reduced mipmap is the CPU's own, not GL's glGenerateMipmap), and the skybox's six
// faces as the layers of one GL_RGB32F array texture (0 without a skybox).
class GlShadeResources {
 public:
  explicit GlShadeResources(const ShadeResources& resources);
  ~GlShadeResources();
  GlShadeResources(const GlShadeResources&) = delete;
  GlShadeResources& operator=(const GlShadeResources&) = delete;

  std::uint32_t lattice() const { return lattice_; }
  std::span<const std::uint32_t> textures() const { return textures_; }
  std::span<const std::int32_t> texture_sizes() const { return sizes_; }  // level 0's side
  std::uint32_t skybox() const { return skybox_; }

 private:
  void upload(const ShadeResources& resources);

  std::uint32_t lattice_ = 0;
  std::vector<std::uint32_t> textures_;
  std::vector<std::int32_t> sizes_;
  std::uint32_t skybox_ = 0;
};

}  // namespace relief::gpu
