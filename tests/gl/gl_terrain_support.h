// Shared by the GL terrain tests: a scene's frame through the CPU reference stages 2-4 and
// through GlTerrain, and the checks docs/gl-backend.md ("Thresholds") derives: on Mesa's
// llvmpipe every stream bit-identical end to end; on any other GL, each GL stage against the
// CPU stage run on the GL's own inputs, within what GLSL 4.50's precision rules allow.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/height_sketch.h"
#include "core/lattice.h"
#include "core/stage_params.h"
#include "gpu/gl_terrain_differences.h"

namespace relief::test {

// True where the GL rounds every operation the shaders use as the CPU does, as measured on it
// (tests/gl/gl_arithmetic.h; llvmpipe: LLVM's IEEE + - * / and sqrt, `precise` honoured): the
// GL stages must then be bit-identical.
bool gl_is_exact();

struct GlTerrainRun {
  std::unique_ptr<NoiseLattice> lattice;  // on the heap: the plan points at it
  std::unique_ptr<HeightSketch> sketch;   // terrain.sketch's texels, or null; the same
  FramePlan plan;
  GridBuffers<float> cpu, gl;
  FbmParams<float> cpu_fbm, gl_fbm;     // as stage 3 ran: the octaves' forms chosen
  gpu::TerrainDifferences differences;  // end to end
};

// `preset` with `overrides` (--set syntax) at a grid of `width` x `height`.
GlTerrainRun run_cpu_and_gl(const std::string& preset, std::vector<std::string> overrides,
                            int width, int height);

// Checks `run` (Catch2 assertions), naming `what`: the octaves' forms, the invalid and padding
// entries and the per-stage bounds always; bit identity end to end where `exact`.
void check_gl_terrain(const GlTerrainRun& run, bool exact, const std::string& what);

}  // namespace relief::test
