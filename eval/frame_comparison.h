// Two renders of one frame compared stage by stage, without any image library: stages 1-4 at
// the grid's vertices (both evaluate every valid vertex), the visibility, and the per-pixel
// outputs where both draw the same triangle. relief crosscheck adds the final images compared
// as idiff compares them (tools/crosscheck.h); docs/gl-backend.md says why a CPU and the GL
// backend may differ and by how much.
#pragma once

#include <cstdint>
#include <vector>

#include "core/grid_buffers.h"
#include "pipeline/frame.h"

namespace relief {

// Stages 1-4, over the vertices valid in both grids.
struct GridDifference {
  std::uint64_t vertices = 0;        // valid in both
  std::uint64_t valid_mismatch = 0;  // valid in one grid only
  double max_height_error = 0;       // world units
  double rms_height_error = 0;       // world units
  double max_normal_angle_deg = 0;   // between the unit normals
  double max_octave_error = 0;       // nu, octaves
  std::vector<float> height_error;   // per vertex |h_a - h_b| (0 where not both valid)
};

GridDifference compare_grids(const GridBuffers<float>& a, const GridBuffers<float>& b);

// The frames' per-pixel outputs (both rendered with every output of FrameOutputs, same size).
struct PixelDifference {
  std::uint64_t pixels = 0;
  std::uint64_t primitive_mismatch = 0;  // pixels whose triangle differs (or is drawn by one)
  double max_depth_error = 0;            // where both drew the same triangle
  double max_normal_angle_deg = 0;
  double max_height_error = 0;  // world units
  double max_octave_error = 0;
  double max_srgb_error = 0;  // codes, over every pixel
  double srgb_psnr = 0;       // dB over the sRGB values / 255 (inf when equal)
  double visibility_share() const {
    return pixels == 0 ? 0.0 : double(primitive_mismatch) / double(pixels);
  }
};

PixelDifference compare_pixels(const FrameImage& a, const FrameImage& b);

}  // namespace relief
