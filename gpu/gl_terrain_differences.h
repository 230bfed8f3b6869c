// How far the GL terrain stages' buffers are from the CPU reference's (the same frame, the
// same parameters): the figures docs/gl-backend.md bounds and tests/gl_terrain_test.cc checks.
// No GL here: the CPU stages and plain arithmetic over GridBuffers.
#pragma once

#include <cstddef>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/stage_params.h"

namespace relief::gpu {

struct TerrainDifferences {
  std::size_t vertices = 0;            // valid in both (the padding columns excluded)
  std::size_t valid_mismatches = 0;    // valid in one only
  std::size_t default_mismatches = 0;  // invalid or padding entries not at their defaults
  std::size_t identical = 0;           // of `vertices`: every stream bit-identical
  std::size_t identical_domain = 0;    // of `vertices`: dx, dz, sigma, nu bit-identical
  std::size_t identical_height = 0;    // of `vertices`: height bit-identical
  std::size_t identical_surface = 0;   // of `vertices`: nx, ny, nz, slope, water_depth
  double domain_max_rel = 0;           // max(|d dx|, |d dz|) / |(dx, dz)|
  double sigma_max_rel = 0;            // |d sigma| / max(|(dx, dz)|, sigma)
  double nu_max_abs = 0;               // |d nu|, octaves
  double height_max_abs = 0;           // |d height|, world units
  double height_rms_abs = 0;
  double normal_max_angle = 0;  // radians between the unit normals
  double slope_max_rel = 0;     // |d slope| / (1 + slope)
  double water_max_abs = 0;     // |d water_depth|, world units
  double bent_max_rel = 0;      // a planet's bend: |d bent position| / |bent position|
};

// `reference`: the CPU's buffers; `gl`: GlTerrain::read_all's, of the same layout.
TerrainDifferences terrain_differences(const GridBuffers<float>& reference,
                                       const GridBuffers<float>& gl);

// The CPU reference stage by stage on the GL's own inputs, so that each GL stage is compared
// with the CPU doing the same arithmetic on the same numbers (a GL stage's rounding is not
// amplified by the later stages): stage 2 as the CPU computes it (`cpu`, run_terrain_stages'
// buffers), stage 3 on the GL's dx, dz, nu and valid (the octaves' forms chosen from them as
// the frame chooses), stage 4 on the GL's dx, dz, valid and heights; on a planet the bend and
// the normals' rotation on the GL's inputs too. Every vertex is computed (no need flags).
GridBuffers<float> staged_reference(const FramePlan& plan, const GridBuffers<float>& cpu,
                                    const GridBuffers<float>& gl);

}  // namespace relief::gpu
