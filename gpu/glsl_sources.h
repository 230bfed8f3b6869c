// The GLSL of gpu/shaders/ (or generated from their templates there), embedded at build time
// (gpu/CMakeLists.txt reads each file into a raw string literal of the generated
// glsl_sources.cc), and the prelude that gives every
// shader the C++ side's constants.
#pragma once

#include <string>
#include <vector>

#include "gpu/gl_program.h"

namespace relief::gpu {

namespace glsl {
extern const char* const kCommon;           // shaders/common.glsl
extern const char* const kLog2Det;          // shaders/log2_det.glsl
extern const char* const kWrapPeriod;       // shaders/wrap_period.glsl
extern const char* const kShadeParams;      // shaders/shade_params.glsl.in, generated
extern const char* const kLattice;          // shaders/shading_lattice.glsl
extern const char* const kProtoTexture;     // shaders/proto_texture.glsl
extern const char* const kSky;              // shaders/sky.glsl
extern const char* const kClouds;           // shaders/clouds.glsl
extern const char* const kWater;            // shaders/water.glsl
extern const char* const kPlanetShading;    // shaders/planet_shading.glsl.in, generated
extern const char* const kGradientShading;  // shaders/gradient_shading.glsl
extern const char* const kTerrainShading;   // shaders/terrain_shading.glsl
extern const char* const kTerrainVert;      // shaders/terrain.vert.in, generated
extern const char* const kTerrainFrag;      // shaders/terrain.frag
extern const char* const kBackgroundVert;   // shaders/background.vert
extern const char* const kBackgroundFrag;   // shaders/background.frag
extern const char* const kTriangles;        // shaders/triangles.comp
}  // namespace glsl

// "#version 450 core" and the constants of stage 8 as the CPU rounds them (each literal is the
// float the C++ code uses, printed with 9 significant digits, which a correctly rounding GLSL
// parser turns back into that float): array sizes, det_math's series, and the guards and
// weights of shade.cc, water.cc, sky.cc, layer_weights.cc and proto_texture.cc.
std::string glsl_prelude();

// The sources of each program, prelude first.
std::vector<GlslSource> terrain_vertex_sources();
std::vector<GlslSource> terrain_fragment_sources();
std::vector<GlslSource> background_vertex_sources();
std::vector<GlslSource> background_fragment_sources();
std::vector<GlslSource> triangle_index_sources();

}  // namespace relief::gpu
