// Stages 5-9 of a frame in OpenGL 4.5 (GLSL 450): the projected grid drawn as indexed
// triangles with the CPU's triangulation and numbering, transformed by the vertex shader as
// core/vertex_transform.cc does, rasterised by GL under glClipControl(GL_LOWER_LEFT,
// GL_ZERO_TO_ONE) with reverse-Z (depth cleared to 0, GL_GREATER, back faces culled, as
// pipeline's frame_raster_state), resolved by GL's interpolators and fine quad derivatives,
// shaded by a fragment shader that follows core/shade.cc operation for operation, and encoded
// to sRGB bytes. The background (sky, fog, open water) is a full-screen pass drawn after the
// terrain, where the terrain left the cleared depth.
// docs/gl-shading.md: the design, the layout rule, and how far the result may differ from the
// CPU's frame and why.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/stage_params.h"
#include "gpu/gl_buffers.h"
#include "gpu/gl_pass_timer.h"
#include "gpu/gl_program.h"

namespace relief::gpu {

// The frame's images (pipeline/frame.h's FrameImage): rows bottom to top; the outputs the
// draw's GlReadback left out are empty. Pixels without terrain: primitive 0xffffffff, depth 0,
// normal, world height and octaves 0.
struct GlFrameImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> srgb;        // 3 per pixel
  std::vector<float> linear;             // 3 per pixel: radiance times the exposure
  std::vector<float> depth;              // window depth, reverse-Z
  std::vector<std::uint32_t> primitive;  // the CPU's triangle number (raster/topology.h)
  std::vector<float> normal;             // 3 per pixel: the renormalised interpolated normal
  std::vector<float> world_height;       // camera y + the camera-relative height, in float
  std::vector<float> octaves;            // interpolated nu; 0 without a nu stream
  double readback_ms = 0;                // the read-back's wall time on the CPU
};

// Which outputs a draw reads back beside the sRGB image, which it always reads (FrameOutputs of
// pipeline/frame.h). An output left out is not read, and its render target is not written
// (glNamedFramebufferDrawBuffers gives its location GL_NONE): none of them changes another.
struct GlReadback {
  bool linear = true;
  bool depth = true;
  bool primitive = true;
  bool normal = true;
  bool world_height = true;
  bool octaves = true;
};

struct GlDrawOptions {
  GlReadback readback;  // every output, as the tests compare them
  // The passes' GPU times (gl_pass_timer.h): the triangle indices, the background and the
  // terrain, each a pass; null: not timed.
  GlPassTimer* timer = nullptr;
  // true: draw `indices` (3 per triangle, vertex indices into the streams; GeoMipMapping's
  // stitched mesh, pipeline/frame_mesh.h), their triangle t as primitive t, instead of the
  // grid's triangulation; none when empty.
  bool indexed = false;
  std::span<const std::uint32_t> indices;
};

class GlTerrainDraw {
 public:
  // Compiles and links the programs. Requires a current GL 4.5 context (headless_gl.h);
  // throws std::runtime_error with the log when a shader does not compile.
  GlTerrainDraw();
  ~GlTerrainDraw();
  GlTerrainDraw(const GlTerrainDraw&) = delete;
  GlTerrainDraw& operator=(const GlTerrainDraw&) = delete;

  // Draws the frame of size shade.width x shade.height. `camera_y`: the camera's height, for
  // the world-height output. Throws std::invalid_argument naming the input that does not fit
  // (grid smaller than 2 x 2, a stream missing, more layers than textures, an image GL cannot
  // hold), and std::runtime_error for a GL error. Leaves the GL state (clip control, depth,
  // culling, buffer and texture bindings) as the draw set it; binds framebuffer 0 again.
  // Reads back what options.readback asks for (by default every output); glGetError is read
  // twice, after the draws and after the read-back.
  GlFrameImage draw(const GlGridStreams& grid, const TransformParams<float>& transform,
                    const ShadeParams<float>& shade, const GlShadeResources& resources,
                    double camera_y, const GlDrawOptions& options = {});

  // Frees what draw() keeps for the next frame of the same size (the render targets, the
  // index buffer, the read-back's staging bytes): the next draw makes them again.
  void release_frame_objects();

  // The members of the blocks that mirror the C++ structs, as the linked programs lay them
  // out: ShadeParamsBlock (std430 storage block of the fragment shaders) and TransformBlock
  // (std140 uniform block of the vertex shader).
  std::vector<GlBlockMember> shade_params_layout() const;
  std::vector<GlBlockMember> transform_params_layout() const;
  int shade_params_size() const;  // GL_BUFFER_DATA_SIZE of the two blocks
  int transform_params_size() const;

 private:
  void build_indices(const GlGridStreams& grid, std::uint32_t triangles);
  // Uploads a mesh's index list into mesh_indices_ (kept while it is large enough).
  void upload_mesh_indices(std::span<const std::uint32_t> indices);
  void set_up_targets(int width, int height, const GlReadback& readback);
  void bind_vertex_streams(const GlGridStreams& grid);
  GlFrameImage read_back(int width, int height, const GlReadback& readback);  // gl_readback.cc

  GlProgram terrain_, background_, triangles_;
  std::uint32_t shade_block_ = 0, transform_block_ = 0, srgb_steps_ = 0;
  std::uint32_t index_buffer_ = 0, no_need_ = 0;
  std::uint32_t index_triangles_ = 0;  // the index buffer's size: kept while the grid's is
  std::uint32_t mesh_indices_ = 0;     // GlDrawOptions::indices, uploaded
  std::size_t mesh_index_bytes_ = 0;   // its size
  std::int64_t max_block_bytes_ = 0;   // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  int max_renderbuffer_size_ = 0;      // GL_MAX_RENDERBUFFER_SIZE
  std::uint32_t terrain_vao_ = 0, empty_vao_ = 0;
  std::uint32_t framebuffer_ = 0;
  std::uint32_t targets_[6] = {};  // linear, srgb, primitive, normal, height/octaves, depth
  std::vector<std::uint8_t> srgb_staging_;  // the sRGB target's RGBA bytes (read_back)
  int target_width_ = 0, target_height_ = 0;
};

}  // namespace relief::gpu
