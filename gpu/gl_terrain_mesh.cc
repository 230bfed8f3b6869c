// GlTerrain's GeoMipMapping passes (terrain.heightfield.geomipmap): the frame's mesh vertices
// uploaded, then stages 2, 3 and 4 of mesh.comp, the GLSL twins of core/heightfield/
// field_mesh.cc's mesh_domain, mesh_heights and mesh_surface (docs/gl-backend.md).
#include <algorithm>
#include <stdexcept>
#include <string>

#include <epoxy/gl.h>

#include "core/limits.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_terrain.h"

namespace relief::gpu {

namespace {

// The B-spline's weights at a knot, as field_mesh.cc rounds them: 1/6 and 4/6 in double.
constexpr double kKnotSide = 1.0 / 6.0, kKnotCentre = 4.0 / 6.0;

}  // namespace

void GlTerrain::set_mesh_vertices(std::span<const std::int32_t> column,
                                  std::span<const std::int32_t> row) {
  require_context("set_mesh_vertices");
  const char* who = "GlTerrain::set_mesh_vertices";
  if (column.size() != row.size()) {
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(column.size()) +
                                " columns and " + std::to_string(row.size()) + " rows");
  }
  if (layout_.pitch % kGroupSize != 0) {
    throw std::invalid_argument(std::string(who) + ": the streams' rows of " +
                                std::to_string(layout_.pitch) +
                                " vertices are not whole work groups (mesh_layout's are)");
  }
  if (column.size() > layout_.size()) {
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(column.size()) +
                                " vertices; the streams hold " + std::to_string(layout_.size()));
  }
  const std::size_t bytes = std::max<std::size_t>(1, column.size()) * 2 * sizeof(std::int32_t);
  if (static_cast<std::int64_t>(bytes) > max_block_bytes_) {
    throw GlError(std::string(who) + ": " + std::to_string(column.size()) + " vertices (" +
                  std::to_string(bytes) + " bytes) exceed this GL's largest storage block (" +
                  std::to_string(max_block_bytes_) + " bytes)");
  }
  if (bytes > mesh_vertex_bytes_) {
    mesh_vertices_ = make_storage_buffer(bytes, "the mesh's vertices");
    mesh_vertex_bytes_ = bytes;
  }
  // The columns, then the rows (mesh.comp reads row k at vertices + k): two uploads, no copy.
  if (!column.empty()) {
    glNamedBufferSubData(mesh_vertices_.get(), 0, GLsizeiptr(column.size_bytes()), column.data());
    glNamedBufferSubData(mesh_vertices_.get(), GLintptr(column.size_bytes()),
                         GLsizeiptr(row.size_bytes()), row.data());
  }
  mesh_vertex_count_ = column.size();
  checkpoint("uploading the mesh's vertices");
}

void GlTerrain::bind_mesh(unsigned int program, bool texels) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingRows, mesh_vertices_.get());
  glProgramUniform1i(program, glGetUniformLocation(program, "u_vertices"),
                     GLint(mesh_vertex_count_));
  if (texels) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSketch, sketch_.get());
    glProgramUniform2i(program, glGetUniformLocation(program, "u_texels"), sketch_width_,
                       sketch_height_);
    glProgramUniform2d(program, glGetUniformLocation(program, "u_knot_weight"), kKnotSide,
                       kKnotCentre);
  }
}

void GlTerrain::mesh_domain(const FieldMesh& field, double camera_x, double camera_z) {
  require_context("mesh_domain");
  require_mesh("GlTerrain::mesh_domain", false);
  const GLuint program = programs_->mesh_domain.get();
  bind_mesh(program, false);
  glProgramUniform4d(program, glGetUniformLocation(program, "u_extent"), field.extent[0],
                     field.extent[1], field.extent[2], field.extent[3]);
  glProgramUniform2i(program, glGetUniformLocation(program, "u_lattice"), field.columns,
                     field.rows);
  glProgramUniform2d(program, glGetUniformLocation(program, "u_camera_xz"), camera_x, camera_z);
  glProgramUniform1f(program, glGetUniformLocation(program, "u_spacing"),
                     static_cast<float>(std::max(field.cell_x, field.cell_z)));
  for (const GlStream s :
       {GlStream::kDx, GlStream::kDz, GlStream::kSigma, GlStream::kNu, GlStream::kValid}) {
    bind_stream(s);
  }
  dispatch(program, layout_.pitch / kGroupSize, layout_.height, "stage 2 (mesh.comp)");
}

void GlTerrain::require_mesh(const char* who, bool texels) const {
  if (mesh_vertices_.get() == 0) {
    throw std::invalid_argument(std::string(who) + ": no mesh vertices (set_mesh_vertices)");
  }
  if (texels && sketch_.get() == 0) {
    throw std::invalid_argument(std::string(who) +
                                ": no field's texels (a GlTerrain made without a sketch)");
  }
}

void GlTerrain::mesh_heights(double camera_above_base) {
  require_context("mesh_heights");
  require_mesh("GlTerrain::mesh_heights", true);
  const GLuint program = programs_->mesh_heights.get();
  bind_mesh(program, true);
  glProgramUniform1d(program, glGetUniformLocation(program, "u_camera_above_base"),
                     camera_above_base);
  bind_stream(GlStream::kHeight);
  dispatch(program, layout_.pitch / kGroupSize, layout_.height, "stage 3 (mesh.comp)");
}

void GlTerrain::mesh_surface(const FieldMesh& field, const SurfaceParams<float>& params) {
  require_context("mesh_surface");
  require_mesh("GlTerrain::mesh_surface", true);
  const GLuint program = programs_->mesh_surface.get();
  bind_mesh(program, true);
  // cell_x, cell_z > 0 (build_field_mesh): the divisions are defined.
  glProgramUniform2d(program, glGetUniformLocation(program, "u_inverse_twice_cell"),
                     0.5 / field.cell_x, 0.5 / field.cell_z);
  glProgramUniform1d(program, glGetUniformLocation(program, "u_max_slope"), limits::kMaxSlope);
  glProgramUniform1i(program, glGetUniformLocation(program, "u_water"),
                     params.water_enabled != 0 ? 1 : 0);
  glProgramUniform1f(program, glGetUniformLocation(program, "u_water_level"), params.water_level);
  for (const GlStream s : {GlStream::kHeight, GlStream::kNx, GlStream::kNy, GlStream::kNz,
                           GlStream::kSlope, GlStream::kWaterDepth}) {
    bind_stream(s);
  }
  dispatch(program, layout_.pitch / kGroupSize, layout_.height, "stage 4 (mesh.comp)");
}

}  // namespace relief::gpu
