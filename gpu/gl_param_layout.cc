#include "gpu/gl_param_layout.h"

#include <algorithm>
#include <cstddef>
#include <type_traits>

#include <epoxy/gl.h>

#include "core/stage_params.h"

namespace relief::gpu {

namespace {

using Domain = DomainParams<float>;
using Fbm = FbmParams<float>;
using Sketch = SketchParams<float>;
using Surface = SurfaceParams<float>;
using Planet = PlanetParams<float>;
using Shade = ShadeParams<float>;

// The structs are uploaded as bytes: no pointers, no padding a GLSL struct would not have.
static_assert(std::is_standard_layout_v<Domain> && std::is_trivially_copyable_v<Domain>);
static_assert(std::is_standard_layout_v<Fbm> && std::is_trivially_copyable_v<Fbm>);
static_assert(std::is_standard_layout_v<Sketch> && std::is_trivially_copyable_v<Sketch>);
static_assert(std::is_standard_layout_v<Surface> && std::is_trivially_copyable_v<Surface>);
static_assert(std::is_standard_layout_v<Planet> && std::is_trivially_copyable_v<Planet>);
static_assert(std::is_standard_layout_v<Shade> && std::is_trivially_copyable_v<Shade>);
static_assert(std::is_standard_layout_v<GlLatticeHeader>);

}  // namespace

// The parameter structs' tables are generated from their field lists (gl_param_tables.cc);
// the lattice's header is no parameter struct, and its block (lattice.glsl) ends in the values.
GlBlockLayout lattice_layout() {
  return {"LatticeBlock",
          0,
          {
              {"lattice_size", offsetof(GlLatticeHeader, size), 0, 0},
              {"lattice_mask", offsetof(GlLatticeHeader, mask), 0, 0},
              {"lattice_values[0]", sizeof(GlLatticeHeader), sizeof(float), sizeof(float), true},
          }};
}

std::vector<std::string> layout_mismatches(unsigned int program, const GlBlockLayout& expected) {
  std::vector<std::string> problems;
  const GLuint block =
      glGetProgramResourceIndex(program, GL_SHADER_STORAGE_BLOCK, expected.block.c_str());
  if (block == GL_INVALID_INDEX) {
    problems.push_back("storage block " + expected.block + " is not active in the program");
    return problems;
  }
  if (expected.size != 0) {
    const GLenum property = GL_BUFFER_DATA_SIZE;
    GLint size = 0;
    glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, block, 1, &property, 1, nullptr,
                           &size);
    const auto gl_size = static_cast<std::size_t>(size);
    if (gl_size < expected.size || gl_size > padded_block_size(expected.size)) {
      problems.push_back(expected.block + ": GLSL size " + std::to_string(size) +
                         " bytes, C++ sizeof " + std::to_string(expected.size));
    }
  }
  for (const GlMemberLayout& m : expected.members) {
    const GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, m.name.c_str());
    if (index == GL_INVALID_INDEX) {
      problems.push_back(expected.block + ": no buffer variable " + m.name);
      continue;
    }
    const GLenum properties[4] = {GL_BLOCK_INDEX, GL_OFFSET, GL_ARRAY_STRIDE,
                                  GL_TOP_LEVEL_ARRAY_STRIDE};
    GLint values[4] = {};
    glGetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 4, properties, 4, nullptr, values);
    const auto differs = [&](const char* what, GLint gl, std::size_t cpp) {
      if (static_cast<std::size_t>(gl) != cpp) {
        problems.push_back(expected.block + ": " + m.name + " " + what + " " + std::to_string(gl) +
                           " in GLSL, " + std::to_string(cpp) + " in C++");
      }
    };
    if (static_cast<GLuint>(values[0]) != block) {
      problems.push_back(expected.block + ": " + m.name + " belongs to another block");
    }
    differs("offset", values[1], m.offset);
    differs("array stride", values[2], m.array_stride);
    if (!(m.top_level_is_scalar_array && values[3] == 0)) {
      differs("top-level array stride", values[3], m.top_level_array_stride);
    }
  }
  // Every buffer variable of the block must be one the table lists.
  const GLenum count_property = GL_NUM_ACTIVE_VARIABLES;
  GLint count = 0;
  glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, block, 1, &count_property, 1, nullptr,
                         &count);
  std::vector<GLint> variables(static_cast<std::size_t>(std::max(count, 0)));
  const GLenum variables_property = GL_ACTIVE_VARIABLES;
  glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, block, 1, &variables_property,
                         static_cast<GLsizei>(variables.size()), nullptr, variables.data());
  for (const GLint v : variables) {
    char name[256] = {};
    glGetProgramResourceName(program, GL_BUFFER_VARIABLE, static_cast<GLuint>(v), sizeof name,
                             nullptr, name);
    const bool listed = std::any_of(expected.members.begin(), expected.members.end(),
                                    [&](const GlMemberLayout& m) { return m.name == name; });
    if (!listed) {
      problems.push_back(expected.block + ": buffer variable " + name +
                         " has no C++ counterpart in the layout table");
    }
  }
  return problems;
}

}  // namespace relief::gpu
