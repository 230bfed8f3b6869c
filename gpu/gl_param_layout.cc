#include "gpu/gl_param_layout.h"

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>

#include <epoxy/gl.h>

#include "core/limits.h"
#include "core/stage_params.h"

namespace relief::gpu {

namespace {

using Domain = DomainParams<float>;
using Fbm = FbmParams<float>;
using Sketch = SketchParams<float>;
using Surface = SurfaceParams<float>;
using Planet = PlanetParams<float>;

// The structs are uploaded as bytes: no pointers, no padding a GLSL struct would not have.
static_assert(std::is_standard_layout_v<Domain> && std::is_trivially_copyable_v<Domain>);
static_assert(std::is_standard_layout_v<Fbm> && std::is_trivially_copyable_v<Fbm>);
static_assert(std::is_standard_layout_v<Sketch> && std::is_trivially_copyable_v<Sketch>);
static_assert(std::is_standard_layout_v<Surface> && std::is_trivially_copyable_v<Surface>);
static_assert(std::is_standard_layout_v<Planet> && std::is_trivially_copyable_v<Planet>);
static_assert(std::is_standard_layout_v<GlLatticeHeader>);

// A scalar member, and an array member (its first element, as GL names it).
#define RELIEF_SCALAR(Struct, prefix, member)      \
  GlMemberLayout {                                 \
    prefix #member, offsetof(Struct, member), 0, 0 \
  }
#define RELIEF_ARRAY(Struct, prefix, member)                                                    \
  GlMemberLayout {                                                                              \
    prefix #member "[0]", offsetof(Struct, member), sizeof(std::declval<Struct>().member[0]), 0 \
  }

}  // namespace

GlBlockLayout domain_params_layout() {
  return {"DomainParamsBlock",
          sizeof(Domain),
          {
              RELIEF_SCALAR(Domain, "domain.", rays.fx),
              RELIEF_SCALAR(Domain, "domain.", rays.fz),
              RELIEF_SCALAR(Domain, "domain.", rays.rx),
              RELIEF_SCALAR(Domain, "domain.", rays.rz),
              RELIEF_SCALAR(Domain, "domain.", rays.ux),
              RELIEF_SCALAR(Domain, "domain.", rays.uz),
              RELIEF_SCALAR(Domain, "domain.", rays.height_above_plane),
              RELIEF_SCALAR(Domain, "domain.", rays.max_distance_sq),
              RELIEF_SCALAR(Domain, "domain.", y0),
              RELIEF_SCALAR(Domain, "domain.", step_y),
              RELIEF_SCALAR(Domain, "domain.", c0),
              RELIEF_SCALAR(Domain, "domain.", c1),
              RELIEF_SCALAR(Domain, "domain.", nu_max),
              RELIEF_SCALAR(Domain, "domain.", min_spacing_sq),
              RELIEF_SCALAR(Domain, "domain.", width),
              RELIEF_SCALAR(Domain, "domain.", height),
              RELIEF_SCALAR(Domain, "domain.", pitch),
              RELIEF_SCALAR(Domain, "domain.", terrain_visible),
              RELIEF_SCALAR(Domain, "domain.", whole_octaves),
          }};
}

GlBlockLayout fbm_params_layout() {
  GlBlockLayout layout{"FbmParamsBlock",
                       sizeof(Fbm),
                       {
                           RELIEF_SCALAR(Fbm, "fbm.", count),
                           RELIEF_SCALAR(Fbm, "fbm.", interpolant),
                           RELIEF_SCALAR(Fbm, "fbm.", warp),
                           RELIEF_ARRAY(Fbm, "fbm.", frequency),
                           RELIEF_ARRAY(Fbm, "fbm.", amplitude),
                           RELIEF_ARRAY(Fbm, "fbm.", offset_x),
                           RELIEF_ARRAY(Fbm, "fbm.", offset_z),
                           RELIEF_ARRAY(Fbm, "fbm.", exact_coordinates),
                           RELIEF_SCALAR(Fbm, "fbm.", period),
                           RELIEF_SCALAR(Fbm, "fbm.", inv_period),
                           RELIEF_SCALAR(Fbm, "fbm.", inv_scale),
                           RELIEF_SCALAR(Fbm, "fbm.", relative_base_height),
                           RELIEF_SCALAR(Fbm, "fbm.", height_scale),
                           RELIEF_SCALAR(Fbm, "fbm.", c1x),
                           RELIEF_SCALAR(Fbm, "fbm.", c1z),
                           RELIEF_SCALAR(Fbm, "fbm.", c2x),
                           RELIEF_SCALAR(Fbm, "fbm.", c2z),
                           RELIEF_SCALAR(Fbm, "fbm.", c3x),
                           RELIEF_SCALAR(Fbm, "fbm.", c3z),
                           RELIEF_SCALAR(Fbm, "fbm.", r0x),
                           RELIEF_SCALAR(Fbm, "fbm.", r0z),
                           RELIEF_SCALAR(Fbm, "fbm.", t0x),
                           RELIEF_SCALAR(Fbm, "fbm.", t0z),
                           RELIEF_SCALAR(Fbm, "fbm.", roughness0),
                           RELIEF_SCALAR(Fbm, "fbm.", guard_sq),
                           RELIEF_SCALAR(Fbm, "fbm.", min_rotation_sq),
                           RELIEF_SCALAR(Fbm, "fbm.", lacunarity),
                       }};
  // The pieces of g_n, float[3][kMaxOctaves]: GL lists an array of arrays by its outer
  // elements, each an array of floats.
  const auto pieces = [&](const char* name, std::size_t offset) {
    for (std::size_t q = 0; q < 3; ++q) {
      layout.members.push_back({"fbm." + std::string(name) + "[" + std::to_string(q) + "][0]",
                                offset + q * limits::kMaxOctaves * sizeof(float), sizeof(float),
                                0});
    }
  };
  pieces("scale_piece", offsetof(Fbm, scale_piece));
  pieces("scale_piece_hi", offsetof(Fbm, scale_piece_hi));
  pieces("scale_piece_lo", offsetof(Fbm, scale_piece_lo));
  return layout;
}

GlBlockLayout sketch_params_layout() {
  return {"SketchParamsBlock",
          sizeof(Sketch),
          {
              RELIEF_SCALAR(Sketch, "sketch.", enabled),
              RELIEF_SCALAR(Sketch, "sketch.", width),
              RELIEF_SCALAR(Sketch, "sketch.", height),
              RELIEF_SCALAR(Sketch, "sketch.", offset_x),
              RELIEF_SCALAR(Sketch, "sketch.", offset_z),
              RELIEF_SCALAR(Sketch, "sketch.", inv_cell_x),
              RELIEF_SCALAR(Sketch, "sketch.", inv_cell_z),
              RELIEF_SCALAR(Sketch, "sketch.", max_x),
              RELIEF_SCALAR(Sketch, "sketch.", max_z),
          }};
}

GlBlockLayout surface_params_layout() {
  return {"SurfaceParamsBlock",
          sizeof(Surface),
          {
              RELIEF_SCALAR(Surface, "surface.", width),
              RELIEF_SCALAR(Surface, "surface.", height),
              RELIEF_SCALAR(Surface, "surface.", pitch),
              RELIEF_SCALAR(Surface, "surface.", water_enabled),
              RELIEF_SCALAR(Surface, "surface.", water_level),
              RELIEF_SCALAR(Surface, "surface.", min_sine_sq),
              RELIEF_SCALAR(Surface, "surface.", max_slope),
          }};
}

GlBlockLayout planet_params_layout() {
  return {"PlanetParamsBlock",
          sizeof(Planet),
          {
              RELIEF_SCALAR(Planet, "planet.", enabled),
              RELIEF_SCALAR(Planet, "planet.", visible),
              RELIEF_SCALAR(Planet, "planet.", radius),
              RELIEF_SCALAR(Planet, "planet.", inv_radius),
              RELIEF_SCALAR(Planet, "planet.", center_distance),
              RELIEF_SCALAR(Planet, "planet.", grid_c),
              RELIEF_SCALAR(Planet, "planet.", blend),
              RELIEF_SCALAR(Planet, "planet.", one_minus_blend),
              RELIEF_SCALAR(Planet, "planet.", theta_h),
              RELIEF_SCALAR(Planet, "planet.", theta_limb),
              RELIEF_SCALAR(Planet, "planet.", alpha_lo),
              RELIEF_SCALAR(Planet, "planet.", theta_lo),
              RELIEF_SCALAR(Planet, "planet.", eq_slope),
          }};
}

GlBlockLayout lattice_layout() {
  return {"LatticeBlock",
          0,
          {
              {"lattice_size", offsetof(GlLatticeHeader, size), 0, 0},
              {"lattice_mask", offsetof(GlLatticeHeader, mask), 0, 0},
              {"lattice_values[0]", sizeof(GlLatticeHeader), sizeof(float), sizeof(float), true},
          }};
}

#undef RELIEF_SCALAR
#undef RELIEF_ARRAY

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
