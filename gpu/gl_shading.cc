#include "gpu/gl_shading.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <epoxy/gl.h>

#include "core/limits.h"
#include "core/srgb.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_param_layout.h"
#include "gpu/glsl_sources.h"

namespace relief::gpu {

namespace {

constexpr GLuint kLocalSize = 256;    // triangles.comp's local_size_x
constexpr GLuint kMaxGroups = 65535;  // GL 4.5's least GL_MAX_COMPUTE_WORK_GROUP_COUNT

// Binding points of the shaders' blocks (shaders/*.glsl).
constexpr GLuint kShadeBinding = 0, kLatticeBinding = 1, kSrgbBinding = 2;  // storage
// The skybox's texture unit, after the layers' (the prelude's RELIEF_SKYBOX_UNIT).
constexpr GLuint kSkyboxUnit = limits::kMaxMaterialLayers;
constexpr GLuint kTransformBinding = 0;                                   // uniform
constexpr GLuint kValidBinding = 0, kNeedBinding = 1, kIndexBinding = 2;  // triangles.comp

// Vertex attributes of terrain.vert: the float streams at 0-8, valid at 9, need at 10, the
// y that stage 5 transforms at 11 and a planet's drop at 12.
constexpr GLuint kValidAttribute = 9, kNeedAttribute = 10;
constexpr GLuint kDropAttribute = 12;

// Colour targets: location k of the fragment shaders is GL_COLOR_ATTACHMENT0 + k.
constexpr GLenum kTargetFormats[5] = {GL_RGBA32F, GL_RGBA8UI, GL_R32UI, GL_RGBA32F, GL_RG32F};

// The least float >= each of srgb_byte's decision points (core/srgb.h, bucket_steps).
std::vector<float> srgb_steps() {
  const auto& points = srgb_detail::decision_points();
  std::vector<float> steps(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    float f = static_cast<float>(points[k]);
    if (double(f) < points[k]) {
      f = std::nextafter(f, 2.0f);
    }
    steps[k] = f;
  }
  return steps;
}

GLuint immutable_buffer(GLsizeiptr size, const void* data, GLbitfield flags) {
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, size, data, flags);
  return buffer;
}

}  // namespace

GlTerrainDraw::GlTerrainDraw()
    : terrain_({{GL_VERTEX_SHADER, terrain_vertex_sources()},
                {GL_FRAGMENT_SHADER, terrain_fragment_sources()}}),
      background_({{GL_VERTEX_SHADER, background_vertex_sources()},
                   {GL_FRAGMENT_SHADER, background_fragment_sources()}}),
      triangles_({{GL_COMPUTE_SHADER, triangle_index_sources()}}) {
  // ShadeParams<float> is uploaded as bytes: the block must place every member where C++
  // does (before any object is made, which a throw would leak).
  std::string problems;
  for (const std::string& problem : layout_mismatches(terrain_.id(), shade_params_block_layout())) {
    problems += "\n  " + problem;
  }
  if (!problems.empty()) {
    throw GlError(
        "the GLSL block of ShadeParams does not match the C++ struct "
        "(gpu/shaders/shade_params.glsl.in against core/stage_params.h):" +
        problems);
  }
  shade_block_ = immutable_buffer(sizeof(ShadeParams<float>), nullptr, GL_DYNAMIC_STORAGE_BIT);
  transform_block_ =
      immutable_buffer(sizeof(TransformParams<float>), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const std::vector<float> steps = srgb_steps();
  srgb_steps_ =
      immutable_buffer(static_cast<GLsizeiptr>(steps.size() * sizeof(float)), steps.data(), 0);
  const std::uint32_t word = 0;
  no_need_ = immutable_buffer(sizeof word, &word, 0);
  glCreateVertexArrays(1, &terrain_vao_);
  glCreateVertexArrays(1, &empty_vao_);
  glCreateFramebuffers(1, &framebuffer_);
  // The limits a draw checks its inputs against, queried once: a query inside the frame would
  // wait for a threaded driver's thread.
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes_);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer_size_);
  check_gl("GlTerrainDraw set-up");
}

GlTerrainDraw::~GlTerrainDraw() {
  const GLuint buffers[] = {shade_block_,  transform_block_, srgb_steps_,
                            index_buffer_, no_need_,         mesh_indices_};
  glDeleteBuffers(6, buffers);
  const GLuint arrays[] = {terrain_vao_, empty_vao_};
  glDeleteVertexArrays(2, arrays);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(6, targets_);
}

void GlTerrainDraw::build_indices(const GlGridStreams& grid, std::uint32_t triangles) {
  const GLsizeiptr bytes = GLsizeiptr(3) * triangles * GLsizeiptr(sizeof(std::uint32_t));
  if (bytes > max_block_bytes_ || static_cast<GLint64>(grid.layout.size()) > max_block_bytes_) {
    throw std::invalid_argument("gpu: a grid of " + std::to_string(grid.layout.width) + " x " +
                                std::to_string(grid.layout.height) +
                                " vertices needs storage buffers larger than this GL's " +
                                std::to_string(max_block_bytes_) + " bytes");
  }
  // The buffer is kept while the grid's triangle count is; its indices are recomputed by every
  // draw (valid and need change with the camera), on the GPU, where they cost a dispatch.
  if (triangles != index_triangles_) {
    glDeleteBuffers(1, &index_buffer_);
    index_buffer_ = immutable_buffer(bytes, nullptr, 0);
    index_triangles_ = triangles;
  }
  const GLuint program = triangles_.id();
  glUseProgram(program);
  glProgramUniform1ui(program, glGetUniformLocation(program, "u_width"),
                      static_cast<GLuint>(grid.layout.width));
  glProgramUniform1ui(program, glGetUniformLocation(program, "u_pitch"),
                      static_cast<GLuint>(grid.layout.pitch));
  glProgramUniform1ui(program, glGetUniformLocation(program, "u_count"), triangles);
  glProgramUniform1i(program, glGetUniformLocation(program, "u_has_need"), grid.need != 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kValidBinding, grid.valid);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNeedBinding, grid.need != 0 ? grid.need : no_need_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndexBinding, index_buffer_);
  // Triangle t = y (groups_x 256) + x: as many rows of groups as 65535 per row needs.
  const GLuint groups = (triangles + kLocalSize - 1) / kLocalSize;
  const GLuint groups_x = std::min(groups, kMaxGroups);
  glDispatchCompute(groups_x, (groups + groups_x - 1) / groups_x, 1);
  glMemoryBarrier(GL_ELEMENT_ARRAY_BARRIER_BIT);
}

void GlTerrainDraw::upload_mesh_indices(std::span<const std::uint32_t> indices) {
  const std::size_t bytes = std::max<std::size_t>(1, indices.size()) * sizeof(std::uint32_t);
  if (bytes > mesh_index_bytes_) {
    glDeleteBuffers(1, &mesh_indices_);
    mesh_indices_ = immutable_buffer(GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    mesh_index_bytes_ = bytes;
  }
  if (!indices.empty()) {
    glNamedBufferSubData(mesh_indices_, 0, GLsizeiptr(indices.size_bytes()), indices.data());
  }
}

void GlTerrainDraw::release_frame_objects() {
  glDeleteRenderbuffers(6, targets_);
  for (GLuint& target : targets_) {
    target = 0;
  }
  target_width_ = 0;
  target_height_ = 0;
  glDeleteBuffers(1, &index_buffer_);
  index_buffer_ = 0;
  index_triangles_ = 0;
  glDeleteBuffers(1, &mesh_indices_);
  mesh_indices_ = 0;
  mesh_index_bytes_ = 0;
  std::vector<std::uint8_t>().swap(srgb_staging_);
}

void GlTerrainDraw::set_up_targets(int width, int height, const GlReadback& readback) {
  if (width != target_width_ || height != target_height_) {
    target_width_ = 0;  // none until they are complete
    target_height_ = 0;
    glDeleteRenderbuffers(6, targets_);
    glCreateRenderbuffers(6, targets_);
    for (int k = 0; k < 5; ++k) {
      glNamedRenderbufferStorage(targets_[k], kTargetFormats[k], width, height);
      glNamedFramebufferRenderbuffer(framebuffer_, GL_COLOR_ATTACHMENT0 + k, GL_RENDERBUFFER,
                                     targets_[k]);
    }
    glNamedRenderbufferStorage(targets_[5], GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferRenderbuffer(framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, targets_[5]);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("gpu: the frame's render targets are incomplete");
    }
    check_gl("render targets");
    target_width_ = width;
    target_height_ = height;
  }
  // Only the targets read back are written (the sRGB one always): the others keep whatever an
  // earlier frame left, and nothing reads them.
  const bool written[5] = {readback.linear, true, readback.primitive, readback.normal,
                           readback.world_height || readback.octaves};
  GLenum draw_buffers[5];
  for (int k = 0; k < 5; ++k) {
    draw_buffers[k] = written[k] ? GLenum(GL_COLOR_ATTACHMENT0 + k) : GLenum(GL_NONE);
  }
  glNamedFramebufferDrawBuffers(framebuffer_, 5, draw_buffers);
}

void GlTerrainDraw::bind_vertex_streams(const GlGridStreams& grid) {
  const GLuint floats[13] = {
      grid.dx,  grid.dz, grid.height, grid.nx,
      grid.ny,  grid.nz, grid.slope,  grid.water_depth,
      grid.nu,  0,       0,           grid.position_y != 0 ? grid.position_y : grid.height,
      grid.drop};
  const GLuint vao = terrain_vao_;
  for (GLuint a = 0; a < 13; ++a) {
    if (a == kValidAttribute || a == kNeedAttribute) {
      continue;  // the byte streams, below
    }
    if (floats[a] == 0) {  // only nu and drop may be missing (draw checks): a constant 0
      glDisableVertexArrayAttrib(vao, a);
      continue;
    }
    glVertexArrayVertexBuffer(vao, a, floats[a], 0, sizeof(float));
    glVertexArrayAttribFormat(vao, a, 1, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, a, a);
    glEnableVertexArrayAttrib(vao, a);
  }
  for (const GLuint a : {kValidAttribute, kNeedAttribute}) {
    const GLuint buffer = a == kValidAttribute ? grid.valid : grid.need;
    if (buffer == 0) {
      glDisableVertexArrayAttrib(vao, a);
      continue;
    }
    glVertexArrayVertexBuffer(vao, a, buffer, 0, 1);
    glVertexArrayAttribIFormat(vao, a, 1, GL_UNSIGNED_BYTE, 0);
    glVertexArrayAttribBinding(vao, a, a);
    glEnableVertexArrayAttrib(vao, a);
  }
  glVertexArrayElementBuffer(vao, index_buffer_);
}

GlFrameImage GlTerrainDraw::draw(const GlGridStreams& grid, const TransformParams<float>& transform,
                                 const ShadeParams<float>& shade, const GlShadeResources& resources,
                                 double camera_y, const GlDrawOptions& options) {
  const GridLayout& layout = grid.layout;
  if (layout.width < 2 || layout.height < 2 || layout.pitch < layout.width) {
    throw std::invalid_argument("gpu: the grid is " + std::to_string(layout.width) + " x " +
                                std::to_string(layout.height) + " (pitch " +
                                std::to_string(layout.pitch) +
                                "); a triangulated grid needs at least 2 x 2 vertices");
  }
  const GLuint required[] = {grid.dx, grid.dz,    grid.height,      grid.nx,   grid.ny,
                             grid.nz, grid.slope, grid.water_depth, grid.valid};
  for (const GLuint name : required) {
    if (name == 0) {
      throw std::invalid_argument(
          "gpu: every grid stream but nu, need, position_y and drop must be a buffer");
    }
  }
  if ((grid.position_y != 0) != (grid.drop != 0)) {
    throw std::invalid_argument("gpu: a planet's grid needs both position_y and drop streams");
  }
  // Gradient shading samples no texture (the scene's resources hold none).
  if (shade.layer_count < 1 ||
      (shade.gradient_enabled == 0 &&
       static_cast<std::size_t>(shade.layer_count) > resources.textures().size()) ||
      static_cast<std::size_t>(shade.layer_count) > limits::kMaxMaterialLayers) {
    throw std::invalid_argument("gpu: shade.layer_count is " + std::to_string(shade.layer_count) +
                                "; there are " + std::to_string(resources.textures().size()) +
                                " proto-textures");
  }
  if (shade.skybox != 0 && resources.skybox() == 0) {
    throw std::invalid_argument("gpu: shade.skybox is set; the resources hold no skybox");
  }
  const int largest = max_renderbuffer_size_;
  if (shade.width < 1 || shade.height < 1 || shade.width > largest || shade.height > largest) {
    throw std::invalid_argument("gpu: the image is " + std::to_string(shade.width) + " x " +
                                std::to_string(shade.height) + "; this GL allows 1 to " +
                                std::to_string(largest) + " a side");
  }
  if (options.indexed && options.indices.size() % 3 != 0) {
    throw std::invalid_argument("gpu: the index list holds " +
                                std::to_string(options.indices.size()) +
                                " indices, not 3 per triangle");
  }
  const std::uint32_t triangles = options.indexed
                                      ? static_cast<std::uint32_t>(options.indices.size() / 3)
                                      : 2u * static_cast<std::uint32_t>(layout.width - 1) *
                                            static_cast<std::uint32_t>(layout.height - 1);
  GlPassTimer* const timer = options.timer;
  if (!options.indexed) {
    if (timer != nullptr) {
      timer->begin("triangle indices (triangles.comp)");
    }
    build_indices(grid, triangles);
    if (timer != nullptr) {
      timer->end();
    }
  } else {
    upload_mesh_indices(options.indices);
  }
  set_up_targets(shade.width, shade.height, options.readback);
  bind_vertex_streams(grid);
  if (options.indexed) {
    glVertexArrayElementBuffer(terrain_vao_, mesh_indices_);
  }
  // The parameter structs as bytes: the blocks mirror their layout (shade_params.glsl).
  glNamedBufferSubData(shade_block_, 0, sizeof shade, &shade);
  glNamedBufferSubData(transform_block_, 0, sizeof transform, &transform);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShadeBinding, shade_block_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLatticeBinding, resources.lattice());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSrgbBinding, srgb_steps_);
  glBindBufferBase(GL_UNIFORM_BUFFER, kTransformBinding, transform_block_);
  for (std::size_t k = 0; k < resources.textures().size(); ++k) {
    glBindTextureUnit(static_cast<GLuint>(k), resources.textures()[k]);
  }
  glBindTextureUnit(kSkyboxUnit, resources.skybox());
  const GLuint program = terrain_.id();
  glProgramUniform1iv(program, glGetUniformLocation(program, "u_texture_size"),
                      static_cast<GLsizei>(resources.texture_sizes().size()),
                      resources.texture_sizes().data());
  glProgramUniform1d(program, glGetUniformLocation(program, "u_camera_y"), camera_y);
  glProgramUniform1f(program, glGetUniformLocation(program, "u_height_origin"), grid.height_origin);
  glVertexAttrib1f(8, 0.0f);               // nu where no stream is bound
  glVertexAttrib1f(kDropAttribute, 0.0f);  // the plane: no drop
  glVertexAttribI1ui(kNeedAttribute, 2u);  // kDraw where no stream is bound

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthRange(0.0, 1.0);
  glViewport(0, 0, shade.width, shade.height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_MULTISAMPLE);
  glDisable(GL_BLEND);
  glDisable(GL_DITHER);
  const float far_depth = 0.0f;  // reverse-Z: infinitely far
  glDepthMask(GL_TRUE);          // a clear writes only where the mask lets it (see below)
  glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &far_depth);

  // The terrain: GREATER depth, back faces culled (the frame's raster state).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glUseProgram(terrain_.id());
  glBindVertexArray(terrain_vao_);
  if (timer != nullptr) {
    timer->begin("terrain (terrain.vert, terrain.frag)");
  }
  if (triangles > 0) {
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * triangles), GL_UNSIGNED_INT, nullptr);
  }
  if (timer != nullptr) {
    timer->end();
  }

  // Then the background where no terrain was drawn: its triangle lies at depth 0, the cleared
  // (infinitely far) value, which only uncovered pixels still hold, since a terrain fragment
  // passes GREATER only above it. The depth test comes before the shader (which writes no
  // depth and discards nothing), so covered pixels cost nothing: drawn first over every pixel,
  // the background took 2.7 ms of an H100's time on the default frame, drawn after the
  // terrain 0.67 ms, the terrain's own time unchanged and every byte the same.
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glUseProgram(background_.id());
  glBindVertexArray(empty_vao_);
  if (timer != nullptr) {
    timer->begin("background (background.frag)");
  }
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (timer != nullptr) {
    timer->end();
  }
  glDepthMask(GL_TRUE);
  check_gl("the triangle indices, the background or the terrain draw");
  glBindVertexArray(0);
  glUseProgram(0);
  GlFrameImage image = read_back(shade.width, shade.height, options.readback);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (grid.nu == 0) {
    image.octaves.assign(image.octaves.size(), 0.0f);
  }
  return image;
}

std::vector<GlBlockMember> GlTerrainDraw::shade_params_layout() const {
  return block_members(terrain_.id(), true, "ShadeParamsBlock");
}

std::vector<GlBlockMember> GlTerrainDraw::transform_params_layout() const {
  return block_members(terrain_.id(), false, "TransformBlock");
}

int GlTerrainDraw::shade_params_size() const {
  return block_size(terrain_.id(), true, "ShadeParamsBlock");
}

int GlTerrainDraw::transform_params_size() const {
  return block_size(terrain_.id(), false, "TransformBlock");
}

}  // namespace relief::gpu
