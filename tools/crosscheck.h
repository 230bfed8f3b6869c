// relief crosscheck's figures: the same frame by a CPU backend and by the GL backend, compared
// stage by stage (pipeline/frame_comparison.h), and the final images as idiff compares them
// (image_compare.h). docs/gl-backend.md says why the two may differ and by how much.
#pragma once

#include <vector>

#include "pipeline/frame.h"
#include "pipeline/frame_comparison.h"
#include "tools/image_compare.h"

namespace relief {

struct FrameDifference {
  PixelDifference pixels;
  CompareResult srgb;    // the sRGB images as values / 255: the verdict crosscheck exits with
  CompareResult linear;  // linear radiance, figures only
  std::vector<float> srgb_difference;  // per pixel, the largest channel difference (rows as stored)
};

FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds);

}  // namespace relief
