#include "gpu/gl_terrain.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"
#include "gpu/gl_shader_prelude.h"

namespace relief::gpu {

namespace {

// Storage blocks the widest program binds (surface.comp: parameters, five inputs, five
// outputs).
constexpr int kMaxBlocksPerProgram = 11;

// Every stage ends with this barrier: the next dispatch, a draw reading the streams as storage
// buffers or vertex attributes, and a read-back all see what the stage wrote.
constexpr GLbitfield kStageBarrier = GL_SHADER_STORAGE_BARRIER_BIT |
                                     GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                                     GL_BUFFER_UPDATE_BARRIER_BIT;

std::string dims(int width, int height, int pitch) {
  return std::to_string(width) + " x " + std::to_string(height) + " (pitch " +
         std::to_string(pitch) + ")";
}

GLint gl_integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

void upload_bytes(const GlName& buffer, std::size_t offset, const void* data, std::size_t bytes) {
  glNamedBufferSubData(buffer.get(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                       data);
}

}  // namespace

GlTerrain::GlTerrain(GridLayout layout, const NoiseLattice& lattice, const HeightSketch* sketch)
    : GlTerrain(nullptr, layout, lattice, sketch) {}

GlTerrain::GlTerrain(std::shared_ptr<const GlTerrainPrograms> programs, GridLayout layout,
                     const NoiseLattice& lattice, const HeightSketch* sketch)
    : layout_(layout) {
  require_gl45("GlTerrain");
  context_ = current_egl_context();
  clear_gl_errors();
  const GridLayout expected = make_grid_layout(layout.width, layout.height);
  if (layout.width < limits::kMinGridSide || layout.width > limits::kMaxGridSide ||
      layout.height < limits::kMinGridSide || layout.height > limits::kMaxGridSide ||
      layout.pitch != expected.pitch) {
    throw std::invalid_argument(
        "GlTerrain: grid " + dims(layout.width, layout.height, layout.pitch) +
        " is not a make_grid_layout grid of sides " + std::to_string(limits::kMinGridSide) +
        " to " + std::to_string(limits::kMaxGridSide) + " (pitch = width rounded up to " +
        std::to_string(limits::kRowAlignFloats) + ")");
  }
  check_lattice("GlTerrain", lattice);

  // What this GL must offer: enough storage blocks and bindings, blocks as large as a stream
  // and as the lattice, and a work group per row.
  const std::size_t stream_bytes = layout.size() * sizeof(float);
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes_);
  GLint max_groups_y = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &max_groups_y);
  GLint max_groups_x = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups_x);
  const GLint blocks = gl_integer(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS);
  const GLint bindings = gl_integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
  check_gl("querying the compute limits");
  if (blocks < kMaxBlocksPerProgram || bindings < kBindingCount) {
    throw GlError("GlTerrain: needs " + std::to_string(kMaxBlocksPerProgram) +
                  " storage blocks per compute shader and " + std::to_string(kBindingCount) +
                  " bindings; this GL offers " + std::to_string(blocks) + " and " +
                  std::to_string(bindings));
  }
  check_sketch("GlTerrain", sketch);
  const std::size_t lattice_bytes = sizeof(GlLatticeHeader) + lattice.values.size() * sizeof(float);
  if (static_cast<GLint64>(std::max(stream_bytes, lattice_bytes)) > max_block_bytes_) {
    throw GlError("GlTerrain: a stream of grid " + dims(layout.width, layout.height, layout.pitch) +
                  " (" + std::to_string(stream_bytes) + " bytes) or the lattice (" +
                  std::to_string(lattice_bytes) +
                  " bytes) exceeds this GL's largest storage block (" +
                  std::to_string(max_block_bytes_) + " bytes)");
  }
  if (layout.height > max_groups_y || (layout.pitch + kGroupSize - 1) / kGroupSize > max_groups_x) {
    throw GlError("GlTerrain: grid " + dims(layout.width, layout.height, layout.pitch) +
                  " needs more compute work groups than this GL dispatches");
  }

  if (programs == nullptr) {
    programs = std::make_shared<const GlTerrainPrograms>(build_terrain_programs());
  } else if (programs->context != context_) {
    throw GlError("GlTerrain: the programs given were built in another OpenGL context");
  }
  programs_ = std::move(programs);
  domain_params_ =
      make_storage_buffer(padded_block_size(sizeof(DomainParams<float>)), "stage 2's parameters");
  fbm_params_ =
      make_storage_buffer(padded_block_size(sizeof(FbmParams<float>)), "stage 3's parameters");
  surface_params_ =
      make_storage_buffer(padded_block_size(sizeof(SurfaceParams<float>)), "stage 4's parameters");
  planet_params_ = make_storage_buffer(padded_block_size(sizeof(PlanetParams<float>)),
                                       "the planet's parameters");
  rows_ = make_storage_buffer(3 * (std::size_t(layout.height) + 2) * sizeof(float),
                              "stage 2's row table");
  reach_ = make_storage_buffer(limits::kMaxOctaves * sizeof(std::uint32_t), "the octave reach");
  for (const GlStream stream : kGlStreams) {
    if (is_bent_stream(stream)) {
      continue;  // a planet frame's: allocated by bend_vertices
    }
    const std::size_t bytes = stream == GlStream::kValid ? layout.size() : stream_bytes;
    streams_[static_cast<int>(stream)] =
        make_storage_buffer(bytes, "stream " + std::string(gl_stream_name(stream)));
  }
  sketch_params_ = make_storage_buffer(padded_block_size(sizeof(SketchParams<float>)),
                                       "the sketch's parameters");
  set_lattice(lattice);
  set_sketch(sketch);
}

void GlTerrain::check_lattice(const char* who, const NoiseLattice& lattice) const {
  const int p = lattice.size;
  if (p < limits::kMinLatticeSize || p > limits::kMaxLatticeSize ||
      !std::has_single_bit(unsigned(p)) || lattice.mask != p - 1 ||
      lattice.values.size() != std::size_t(p) * std::size_t(p)) {
    throw std::invalid_argument(std::string(who) + ": the lattice (size " + std::to_string(p) +
                                ", " + std::to_string(lattice.values.size()) +
                                " values) is not a make_noise_lattice one");
  }
}

void GlTerrain::check_sketch(const char* who, const HeightSketch* sketch) const {
  if (sketch == nullptr) {
    return;
  }
  const std::size_t samples = sketch->level_width.empty()
                                  ? std::size_t(sketch->width) * std::size_t(sketch->height)
                                  : field_levels_samples(sketch->width, sketch->height);
  if (sketch->width < 2 || sketch->height < 2 || sketch->heights.size() != samples) {
    throw std::invalid_argument(
        std::string(who) + ": the sketch (" + std::to_string(sketch->width) + " x " +
        std::to_string(sketch->height) + ", " + std::to_string(sketch->heights.size()) +
        " heights) is not a make_height_sketch one");
  }
  const std::size_t bytes = sketch->heights.size() * sizeof(float);
  if (static_cast<GLint64>(bytes) > max_block_bytes_) {
    throw GlError(std::string(who) + ": the sketch or height field (" +
                  std::to_string(sketch->width) + "x" + std::to_string(sketch->height) +
                  " samples" + (sketch->levels() > 1 ? " and their levels of detail, " : ", ") +
                  std::to_string(bytes) + " bytes) exceeds this GL's largest storage block (" +
                  std::to_string(max_block_bytes_) +
                  " bytes); use a smaller terrain.heightfield.file or terrain.sketch.image, or "
                  "another backend");
  }
}

void GlTerrain::set_lattice(const NoiseLattice& lattice) {
  require_context("set_lattice");
  check_lattice("GlTerrain::set_lattice", lattice);
  const std::size_t bytes = sizeof(GlLatticeHeader) + lattice.values.size() * sizeof(float);
  if (static_cast<GLint64>(bytes) > max_block_bytes_) {
    throw GlError("GlTerrain::set_lattice: the lattice (" + std::to_string(bytes) +
                  " bytes) exceeds this GL's largest storage block (" +
                  std::to_string(max_block_bytes_) + " bytes)");
  }
  lattice_size_ = 0;  // unusable until the upload below has succeeded
  if (bytes != lattice_bytes_) {
    lattice_ = make_storage_buffer(bytes, "the noise lattice");
    lattice_bytes_ = bytes;
  }
  const GlLatticeHeader header{lattice.size, lattice.mask};
  upload_bytes(lattice_, 0, &header, sizeof header);
  upload_bytes(lattice_, sizeof header, lattice.values.data(),
               lattice.values.size() * sizeof(float));
  check_gl("uploading the noise lattice");  // once per scene: always checked
  lattice_size_ = lattice.size;
}

void GlTerrain::set_sketch(const HeightSketch* sketch) {
  require_context("set_sketch");
  check_sketch("GlTerrain::set_sketch", sketch);
  sketch_width_ = 0;  // none until the upload below has succeeded
  sketch_height_ = 0;
  if (sketch == nullptr) {
    sketch_ = GlName();
    sketch_bytes_ = 0;
    return;
  }
  const std::size_t bytes = sketch->heights.size() * sizeof(float);
  if (bytes != sketch_bytes_) {
    sketch_ = make_storage_buffer(bytes, "the sketch");
    sketch_bytes_ = bytes;
  }
  upload_bytes(sketch_, 0, sketch->heights.data(), bytes);
  check_gl("uploading the sketch");
  sketch_width_ = sketch->width;
  sketch_height_ = sketch->height;
}

void GlTerrain::require_context(const char* who) const {
  if (current_egl_context() != context_) {
    throw GlError(std::string("GlTerrain::") + who +
                  ": the OpenGL context this GlTerrain was made in is not current on this thread");
  }
  if (checks_ == GlErrorChecks::kEachCall) {
    clear_gl_errors();
  }
}

void GlTerrain::checkpoint(const std::string& what) const {
  if (checks_ == GlErrorChecks::kEachCall) {
    check_gl(what);
  }
}

void GlTerrain::bind_stream(GlStream stream) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, stream_binding(stream), buffer(stream));
}

void GlTerrain::dispatch(unsigned int program, int groups_x, int groups_y,
                         const std::string& what) const {
  checkpoint("binding the buffers of " + what);
  if (timer_ != nullptr) {
    timer_->begin(what);
  }
  glUseProgram(program);
  glDispatchCompute(static_cast<GLuint>(groups_x), static_cast<GLuint>(groups_y), 1);
  glMemoryBarrier(kStageBarrier);
  glUseProgram(0);
  if (timer_ != nullptr) {
    timer_->end();
  }
  checkpoint(what);
}

void GlTerrain::run(const TerrainParams<float>& params) {
  project_domain(params.domain, params.domain_rows, params.planet);
  evaluate_fbm(params.fbm, OctaveForms::kFromReach);
  add_sketch(params.sketch);
  bend_vertices(params.planet);
  surface_pass(params.surface);
  bend_normals(params.planet);
}

void GlTerrain::project_domain(const DomainParams<float>& params, const DomainRows<float>& rows,
                               const PlanetParams<float>& planet) {
  require_context("project_domain");
  const char* who = "GlTerrain::project_domain";
  require_grid_size(who, "DomainParams::width", params.width, layout_.width);
  require_grid_size(who, "DomainParams::height", params.height, layout_.height);
  require_grid_size(who, "DomainParams::pitch", params.pitch, layout_.pitch);
  const std::size_t row_count = std::size_t(layout_.height) + 2;
  require_grid_size(who, "DomainRows::descent.size()", rows.descent.size(), row_count);
  require_grid_size(who, "DomainRows::x0.size()", rows.x0.size(), row_count);
  require_grid_size(who, "DomainRows::step_x.size()", rows.step_x.size(), row_count);
  upload_bytes(domain_params_, 0, &params, sizeof params);
  const std::size_t row_bytes = row_count * sizeof(float);
  upload_bytes(rows_, 0, rows.descent.data(), row_bytes);
  upload_bytes(rows_, row_bytes, rows.x0.data(), row_bytes);
  upload_bytes(rows_, 2 * row_bytes, rows.step_x.data(), row_bytes);
  upload_planet(planet);
  checkpoint("uploading stage 2's parameters");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingParams, domain_params_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRows, rows_.get());
  for (const GlStream s :
       {GlStream::kDx, GlStream::kDz, GlStream::kSigma, GlStream::kNu, GlStream::kValid}) {
    bind_stream(s);
  }
  dispatch(programs_->domain.get(), (layout_.pitch + kGroupSize - 1) / kGroupSize, layout_.height,
           "stage 2 (domain.comp)");
}

void GlTerrain::evaluate_fbm(const FbmParams<float>& params, OctaveForms forms) {
  require_context("evaluate_fbm");
  const char* who = "GlTerrain::evaluate_fbm";
  if (params.count < 0 || params.count > limits::kMaxOctaves) {
    throw std::invalid_argument(std::string(who) + ": FbmParams::count is " +
                                std::to_string(params.count) + ", allowed 0 to " +
                                std::to_string(limits::kMaxOctaves));
  }
  if (params.interpolant < 0 || params.interpolant > 2) {
    throw std::invalid_argument(std::string(who) + ": FbmParams::interpolant is " +
                                std::to_string(params.interpolant) +
                                ", allowed 0 (linear), 1 (cubic), 2 (quintic)");
  }
  if (params.period != float(lattice_size_) || params.inv_period != 1.0f / params.period) {
    throw std::invalid_argument(std::string(who) + ": FbmParams::period is " +
                                std::to_string(params.period) + ", the lattice's size is " +
                                std::to_string(lattice_size_));
  }
  upload_bytes(fbm_params_, 0, &params, sizeof params);
  checkpoint("uploading stage 3's parameters");
  const int groups_x = (layout_.pitch + kGroupSize - 1) / kGroupSize;
  for (const GLuint program : {programs_->reach.get(), programs_->fbm.get()}) {
    glProgramUniform1i(program, glGetUniformLocation(program, "grid_pitch"), layout_.pitch);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingParams, fbm_params_.get());
  for (const GlStream s :
       {GlStream::kDx, GlStream::kDz, GlStream::kNu, GlStream::kValid, GlStream::kHeight}) {
    bind_stream(s);
  }
  if (forms == OctaveForms::kFromReach) {
    // octave_reach, then choose_coordinate_forms writing FbmParams::exact_coordinates.
    glClearNamedBufferData(reach_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingReach, reach_.get());
    dispatch(programs_->reach.get(), groups_x, layout_.height, "the octave reach (reach.comp)");
    dispatch(programs_->forms.get(), 1, 1, "the coordinate forms (forms.comp)");
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLattice, lattice_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingMask,
                   use_need_ ? need_.get() : buffer(GlStream::kValid));
  dispatch(programs_->fbm.get(), groups_x, layout_.height, "stage 3 (fbm.comp)");
}

void GlTerrain::add_sketch(const SketchParams<float>& params) {
  require_context("add_sketch");
  if (params.enabled == 0) {
    return;
  }
  const char* who = "GlTerrain::add_sketch";
  if (sketch_.get() == 0) {
    throw std::invalid_argument(std::string(who) +
                                ": SketchParams::enabled is 1 but this GlTerrain has no sketch");
  }
  require_grid_size(who, "SketchParams::width", params.width, sketch_width_);
  require_grid_size(who, "SketchParams::height", params.height, sketch_height_);
  upload_bytes(sketch_params_, 0, &params, sizeof params);
  checkpoint("uploading the sketch's parameters");
  const GLuint program = programs_->sketch.get();
  glProgramUniform1i(program, glGetUniformLocation(program, "grid_pitch"), layout_.pitch);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingParams, sketch_params_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSketch, sketch_.get());
  for (const GlStream s : {GlStream::kDx, GlStream::kDz, GlStream::kNu, GlStream::kHeight}) {
    bind_stream(s);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingMask,
                   use_need_ ? need_.get() : buffer(GlStream::kValid));
  dispatch(program, (layout_.pitch + kGroupSize - 1) / kGroupSize, layout_.height,
           "stage 3's sketch (sketch.comp)");
}

void GlTerrain::surface_pass(const SurfaceParams<float>& params) {
  require_context("surface_pass");
  const char* who = "GlTerrain::surface_pass";
  require_grid_size(who, "SurfaceParams::width", params.width, layout_.width);
  require_grid_size(who, "SurfaceParams::height", params.height, layout_.height);
  require_grid_size(who, "SurfaceParams::pitch", params.pitch, layout_.pitch);
  upload_bytes(surface_params_, 0, &params, sizeof params);
  checkpoint("uploading stage 4's parameters");
  const GLuint program = programs_->surface.get();
  glProgramUniform1i(program, glGetUniformLocation(program, "use_need"), use_need_ ? 1 : 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingParams, surface_params_.get());
  for (const GlStream s :
       {GlStream::kDx, GlStream::kDz, GlStream::kHeight, GlStream::kValid, GlStream::kNx,
        GlStream::kNy, GlStream::kNz, GlStream::kSlope, GlStream::kWaterDepth}) {
    bind_stream(s);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingMask,
                   use_need_ ? need_.get() : buffer(GlStream::kValid));
  dispatch(program, (layout_.pitch + kGroupSize - 1) / kGroupSize, layout_.height,
           "stage 4 (surface.comp)");
}

}  // namespace relief::gpu
