// relief crosscheck's figures: the same frame by a CPU backend and by the GL backend, compared
// stage by stage. Stages 1-4 at the grid's vertices (both evaluate every valid vertex), the
// visibility and the per-pixel outputs where both draw the same triangle, and the final image
// as idiff compares images (image_compare.h). docs/gl-backend.md says why the two may differ
// and by how much.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/grid_buffers.h"
#include "pipeline/frame.h"
#include "tools/image_compare.h"

namespace relief {

// Stages 1-4, over the vertices valid in both grids.
struct GridDifference {
  std::uint64_t vertices = 0;        // valid in both
  std::uint64_t valid_mismatch = 0;  // valid in one grid only
  double max_height_error = 0;       // world units
  double rms_height_error = 0;       // world units
  double max_normal_angle_deg = 0;   // between the unit normals
  double max_octave_error = 0;       // nu, octaves
  std::vector<float> height_error;   // per vertex |h_cpu - h_gl| (0 where not both valid)
};

GridDifference compare_grids(const GridBuffers<float>& cpu, const GridBuffers<float>& gl);

// The frames' outputs (both rendered with every output of FrameOutputs).
struct FrameDifference {
  std::uint64_t pixels = 0;
  std::uint64_t primitive_mismatch = 0;  // pixels whose triangle differs (or is drawn by one)
  double max_depth_error = 0;            // where both drew the same triangle
  double max_normal_angle_deg = 0;
  double max_height_error = 0;  // world units
  double max_octave_error = 0;
  CompareResult srgb;  // the sRGB images as values / 255: the verdict relief crosscheck exits with
  CompareResult linear;  // linear radiance, figures only (thresholds of `srgb` not applied)
  std::vector<float> srgb_difference;  // per pixel, the largest channel difference (codes / 255)
  double visibility_share() const {
    return pixels == 0 ? 0.0 : double(primitive_mismatch) / double(pixels);
  }
};

FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds);

}  // namespace relief
