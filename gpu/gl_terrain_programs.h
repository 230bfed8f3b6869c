// The compute programs of gl_terrain.h, each assembled from the prelude (gl_shader_prelude.h),
// the parameter structs (params.glsl, generated from shaders/params.glsl.in), the shared
// functions it calls and its stage's .comp file, and checked against the C++ parameter layouts
// (gl_param_layout.h).
#pragma once

#include <string_view>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/gl_param_layout.h"

namespace relief::gpu {

struct GlTerrainPrograms {
  GlName domain;        // stage 2: domain.comp
  GlName reach;         // octave_reach: reach.comp
  GlName forms;         // choose_coordinate_forms: forms.comp
  GlName fbm;           // stage 3: fbm.comp
  GlName sketch;        // stage 3, §3's sketch: sketch.comp
  GlName surface;       // stage 4: surface.comp
  GlName bend;          // a planet's bend after stage 3: bend.comp
  GlName bend_normals;  // a planet's normals into the bent frame after stage 4
  // GeoMipMapping's vertex stages 2, 3 and 4: mesh.comp, one program per stage.
  GlName mesh_domain, mesh_heights, mesh_surface;

  // The EGL context they were built in (current_egl_context()): a GlTerrain given them checks
  // that it is its own.
  void* context = nullptr;
};

// The parameter blocks each program reads, with the layouts they must have.
struct GlProgramBlocks {
  std::string_view program;
  std::vector<GlBlockLayout> blocks;
};
std::vector<GlProgramBlocks> terrain_program_blocks();

// Builds every program; throws GlError with the compiler's log, or with every layout
// mismatch found, naming the program.
GlTerrainPrograms build_terrain_programs();

// The program of `programs` named as in terrain_program_blocks() ("domain", "fbm", ...).
unsigned int program_named(const GlTerrainPrograms& programs, std::string_view name);

}  // namespace relief::gpu
