// The GL terrain stages' contracts that are not numbers: the GLSL parameter blocks mirror the
// C++ structs of core/stage_params.h member by member (offsets, array strides, top-level
// strides and sizes queried from the linked programs against offsetof and sizeof), the layout
// check catches a drifted declaration, the streams are tight arrays, and every failure (no
// context, a GL error, a shader that does not compile, parameters that do not fit) is an
// exception with a message naming it, never a crash.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <epoxy/gl.h>
#include <catch2/catch.hpp>

#include "core/lattice.h"
#include "core/limits.h"
#include "core/stage_params.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_objects.h"
#include "gpu/gl_param_layout.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_shader_sources.h"
#include "gpu/gl_terrain.h"
#include "gpu/gl_terrain_programs.h"
#include "tests/gl/gl_test_context.h"

namespace relief {
namespace {

GLint resource_property(GLuint program, GLenum interface, GLuint index, GLenum property) {
  GLint value = 0;
  glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
  return value;
}

std::size_t cpp_size(std::string_view block) {
  if (block == "DomainParamsBlock") {
    return sizeof(DomainParams<float>);
  }
  if (block == "FbmParamsBlock") {
    return sizeof(FbmParams<float>);
  }
  if (block == "SketchParamsBlock") {
    return sizeof(SketchParams<float>);
  }
  if (block == "SurfaceParamsBlock") {
    return sizeof(SurfaceParams<float>);
  }
  if (block == "PlanetParamsBlock") {
    return sizeof(PlanetParams<float>);
  }
  return 0;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& line : lines) {
    s += line + "\n";
  }
  return s;
}

TEST_CASE("glParameterBlocksMirrorTheCppStructsMemberByMember", "[gl]") {
  test::gl_context();
  const gpu::GlTerrainPrograms programs = gpu::build_terrain_programs();
  int blocks_checked = 0;
  for (const gpu::GlProgramBlocks& entry : gpu::terrain_program_blocks()) {
    const GLuint program = gpu::program_named(programs, entry.program);
    for (const gpu::GlBlockLayout& block : entry.blocks) {
      INFO(entry.program << ": " << block.block);
      // Offsets, array strides, top-level strides and the block size, against offsetof and
      // sizeof; every buffer variable of the block has a C++ counterpart.
      const std::vector<std::string> problems = gpu::layout_mismatches(program, block);
      INFO(joined(problems));
      CHECK(problems.empty());
      // And every C++ member has a GLSL one: the members the table lists cover the struct's
      // bytes exactly (all are 4-byte scalars or arrays of them; an array's element count is
      // the program's GL_ARRAY_SIZE).
      if (block.size != 0) {
        std::size_t covered = 0;
        for (const gpu::GlMemberLayout& m : block.members) {
          const GLuint index =
              glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, m.name.c_str());
          REQUIRE(index != GL_INVALID_INDEX);
          covered +=
              4 * std::size_t(resource_property(program, GL_BUFFER_VARIABLE, index, GL_ARRAY_SIZE));
        }
        CHECK(covered == cpp_size(block.block));
        CHECK(block.size == cpp_size(block.block));
      }
      ++blocks_checked;
    }
  }
  CHECK(blocks_checked == 9);  // the planet's block in domain, bend and bend_normals too
}

TEST_CASE("glStreamBlocksAreTightArraysAtOffsetZero", "[gl]") {
  test::gl_context();
  const gpu::GlTerrainPrograms programs = gpu::build_terrain_programs();
  for (const gpu::GlProgramBlocks& entry : gpu::terrain_program_blocks()) {
    const GLuint program = gpu::program_named(programs, entry.program);
    GLint blocks = 0;
    glGetProgramInterfaceiv(program, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &blocks);
    for (GLint b = 0; b < blocks; ++b) {
      char name[128] = {};
      glGetProgramResourceName(program, GL_SHADER_STORAGE_BLOCK, GLuint(b), sizeof name, nullptr,
                               name);
      const std::string block = name;
      if (block.find("Params") != std::string::npos || block == "LatticeBlock") {
        continue;  // checked member by member above
      }
      // A stream (dx, ..., valid, need), the row table or the reach: one array of 4-byte
      // elements from offset 0, the CPU's flat array.
      const GLint variables =
          resource_property(program, GL_SHADER_STORAGE_BLOCK, GLuint(b), GL_NUM_ACTIVE_VARIABLES);
      INFO(entry.program << ": " << block);
      REQUIRE(variables == 1);
      GLint variable = 0;
      const GLenum active = GL_ACTIVE_VARIABLES;
      glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, GLuint(b), 1, &active, 1, nullptr,
                             &variable);
      CHECK(resource_property(program, GL_BUFFER_VARIABLE, GLuint(variable), GL_OFFSET) == 0);
      CHECK(resource_property(program, GL_BUFFER_VARIABLE, GLuint(variable), GL_ARRAY_STRIDE) == 4);
    }
  }
}

// A GLSL declaration that drifted from the C++ struct (two members swapped, an array added)
// is reported member by member.
TEST_CASE("glLayoutCheckCatchesADriftedDeclaration", "[gl]") {
  test::gl_context();
  std::string params(gpu::shader_file("params.glsl"));
  const std::string original = "  float y0, step_y;\n";
  const std::size_t at = params.find(original);
  REQUIRE(at != std::string::npos);
  params.replace(at, original.size(), "  float step_y, y0;\n  float extra[4];\n");
  const std::string prelude = gpu::shader_prelude();
  const std::vector<std::string_view> sources = {prelude, params, gpu::shader_file("det_math.glsl"),
                                                 gpu::shader_file("log2_det.glsl"),
                                                 gpu::shader_file("domain.comp")};
  const gpu::GlName program = gpu::link_compute_program(sources, "drifted domain.comp");
  const std::vector<std::string> problems =
      gpu::layout_mismatches(program.get(), gpu::domain_params_layout());
  const std::string all = joined(problems);
  INFO(all);
  CHECK(all.find("domain.y0 offset") != std::string::npos);
  CHECK(all.find("domain.step_y offset") != std::string::npos);
  CHECK(all.find("domain.extra[0] has no C++ counterpart") != std::string::npos);
  CHECK(all.find("GLSL size") != std::string::npos);
}

TEST_CASE("glTerrainWithoutAContextThrowsAClearError", "[gl]") {
  test::gl_context();  // current on the test thread, not on the one below
  const NoiseLattice lattice = make_noise_lattice(1, 16);
  std::string message;
  std::thread other([&] {
    try {
      gpu::GlTerrain terrain(make_grid_layout(32, 32), lattice);
      message = "no exception";
    } catch (const gpu::GlError& e) {
      message = e.what();
    }
  });
  other.join();
  CHECK(message.find("no OpenGL context is current") != std::string::npos);

  // An object used from a thread where its context is not current.
  gpu::GlTerrain terrain(make_grid_layout(32, 32), lattice);
  std::thread user([&] {
    try {
      std::vector<float> height(terrain.layout().size());
      terrain.read(gpu::GlStream::kHeight, height);
      message = "no exception";
    } catch (const gpu::GlError& e) {
      message = e.what();
    }
  });
  user.join();
  CHECK(message.find("is not current on this thread") != std::string::npos);
}

TEST_CASE("glTerrainReportsGlErrorsAndBadParametersWithoutCrashing", "[gl]") {
  test::gl_context();
  const NoiseLattice lattice = make_noise_lattice(1, 32);
  const GridLayout layout = make_grid_layout(33, 20);

  SECTION("a shader that does not compile") {
    const std::string prelude = gpu::shader_prelude();
    const std::vector<std::string_view> sources = {prelude, "void main() { undeclared = 1; }\n"};
    CHECK_THROWS_WITH(
        gpu::link_compute_program(sources, "broken.comp"),
        Catch::Contains("broken.comp failed to compile") && Catch::Contains("undeclared"));
  }
  SECTION("a GL error: a stream deleted behind the object's back") {
    gpu::GlTerrain terrain(layout, lattice);
    const GLuint dx = terrain.buffer(gpu::GlStream::kDx);
    glDeleteBuffers(1, &dx);
    FbmParams<float> params;
    params.period = 32.0f;
    params.inv_period = 1.0f / 32.0f;
    CHECK_THROWS_AS(terrain.evaluate_fbm(params, gpu::OctaveForms::kAsGiven), gpu::GlError);
    CHECK_THROWS_WITH(terrain.evaluate_fbm(params, gpu::OctaveForms::kAsGiven),
                      Catch::Contains("OpenGL error GL_INVALID_OPERATION"));
    CHECK(glGetError() == GL_NO_ERROR);  // reported, not left pending
  }
  SECTION("parameters that do not fit the grid, the lattice or the limits") {
    gpu::GlTerrain terrain(layout, lattice);
    SurfaceParams<float> surface;
    surface.width = layout.width + 1;
    surface.height = layout.height;
    surface.pitch = layout.pitch;
    CHECK_THROWS_WITH(terrain.surface_pass(surface), Catch::Contains("SurfaceParams::width is 34"));
    FbmParams<float> fbm;
    fbm.period = 32.0f;
    fbm.inv_period = 1.0f / 32.0f;
    fbm.interpolant = 7;
    CHECK_THROWS_WITH(terrain.evaluate_fbm(fbm), Catch::Contains("FbmParams::interpolant is 7"));
    fbm.interpolant = 0;
    fbm.count = limits::kMaxOctaves + 1;
    CHECK_THROWS_WITH(terrain.evaluate_fbm(fbm), Catch::Contains("FbmParams::count is 25"));
    fbm.count = 1;
    fbm.period = 64.0f;
    CHECK_THROWS_WITH(terrain.evaluate_fbm(fbm), Catch::Contains("FbmParams::period is 64"));
    std::vector<float> short_stream(layout.size() - 1);
    CHECK_THROWS_WITH(terrain.read(gpu::GlStream::kNu, short_stream),
                      Catch::Contains("the size of stream nu"));
    CHECK_THROWS_AS(terrain.read(gpu::GlStream::kValid, short_stream), std::invalid_argument);
    CHECK_THROWS_WITH(gpu::GlTerrain(GridLayout{33, 20, 33}, lattice),
                      Catch::Contains("not a make_grid_layout grid"));
    // A grid whose streams exceed this GL's largest storage block (llvmpipe: 128 MiB) is
    // refused before anything is allocated.
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    const GridLayout huge = make_grid_layout(limits::kMaxGridSide, limits::kMaxGridSide);
    if (static_cast<GLint64>(huge.size() * sizeof(float)) > max_block) {
      CHECK_THROWS_WITH(gpu::GlTerrain(huge, lattice), Catch::Contains("largest storage block"));
    }
    NoiseLattice broken = lattice;
    broken.values.pop_back();
    CHECK_THROWS_WITH(gpu::GlTerrain(layout, broken), Catch::Contains("the lattice"));
  }
}

}  // namespace
}  // namespace relief
