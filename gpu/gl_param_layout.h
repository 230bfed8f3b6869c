// The parameter structs as the GLSL storage blocks must lay them out: for every member of
// the stage parameter structs (core/stage_params.h) and the lattice header (below), its GLSL
// buffer variable name, its C++ offsetof() and array strides. GlTerrain and GlTerrainDraw
// upload the C++ structs' bytes unchanged, so these must be the offsets and strides the linked
// programs report; layout_mismatches() compares them (both refuse to run otherwise, and
// tests/gl_terrain_layout_test.cc checks it). The parameter structs' tables are generated at
// build time from the same field lists as their GLSL declarations (core/stage_param_fields.h,
// gpu/param_codegen.cc), so this checks the generator against the compiler's layout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace relief::gpu {

// The head of the lattice's storage buffer: NoiseLattice's size and mask; its values follow,
// row-major (values[j P + i]), at offset sizeof(GlLatticeHeader).
struct GlLatticeHeader {
  std::int32_t size = 0;  // P
  std::int32_t mask = 0;  // P - 1
};

struct GlMemberLayout {
  std::string name;              // as glGetProgramResourceIndex takes it
  std::size_t offset = 0;        // offsetof in the C++ struct (GL_OFFSET)
  std::size_t array_stride = 0;  // 0 for a scalar (GL_ARRAY_STRIDE)
  // GL_TOP_LEVEL_ARRAY_STRIDE: 0 for the members of a parameter struct (the block's one
  // top-level member, a struct, is no array). For a top-level array of scalars the
  // specification asks for the element stride, which Mesa reports as 0: either is accepted
  // there (top_level_is_scalar_array), its GL_ARRAY_STRIDE being the same stride, checked.
  std::size_t top_level_array_stride = 0;
  bool top_level_is_scalar_array = false;
};

// The block's size: GL_BUFFER_DATA_SIZE may exceed sizeof by the padding of the block to a
// multiple of 16 bytes (Mesa pads DomainParams' 72 bytes to 80); buffers are allocated at
// padded_block_size().
inline constexpr std::size_t kBlockSizeAlign = 16;
inline constexpr std::size_t padded_block_size(std::size_t bytes) {
  return (bytes + kBlockSizeAlign - 1) / kBlockSizeAlign * kBlockSizeAlign;
}

struct GlBlockLayout {
  std::string block;     // the GLSL block name
  std::size_t size = 0;  // sizeof the C++ struct; 0: the block ends in a runtime array
  std::vector<GlMemberLayout> members;
};

GlBlockLayout domain_params_layout();   // DomainParamsBlock { DomainParams domain; }
GlBlockLayout fbm_params_layout();      // FbmParamsBlock { FbmParams fbm; }
GlBlockLayout sketch_params_layout();   // SketchParamsBlock { SketchParams sketch; }
GlBlockLayout surface_params_layout();  // SurfaceParamsBlock { SurfaceParams surface; }
GlBlockLayout planet_params_layout();   // PlanetParamsBlock { PlanetParams planet; }
GlBlockLayout lattice_layout();         // LatticeBlock: GlLatticeHeader, then the values
// ShadeParamsBlock { the members of ShadeParams<float> } (shade_params.glsl), named as GL names
// the members of a block with an instance name: "ShadeParamsBlock.width".
GlBlockLayout shade_params_block_layout();

// Every difference between `expected` and that block as `program` linked it: a member the
// program lacks or places elsewhere, a different stride, a block size outside [sizeof,
// padded_block_size(sizeof)], or a buffer variable of the block that `expected` does not list.
// Empty when they agree. The block must be active.
std::vector<std::string> layout_mismatches(unsigned int program, const GlBlockLayout& expected);

}  // namespace relief::gpu
