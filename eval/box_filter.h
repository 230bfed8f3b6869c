// N x N samples per pixel averaged into one, in linear radiance: the reduction of a frame
// rendered N times larger each way (relief sweep's supersampled configurations). The same
// arithmetic as the ground truth's reduction (ground_truth.cc): each pixel's samples summed in
// double in a fixed order, row by row, divided by N^2, rounded once to float.
#pragma once

#include <span>
#include <vector>

namespace relief {

// `samples`: RGB floats, sample_width x sample_height, rows bottom to top. Precondition: n >= 1,
// sample_width and sample_height positive multiples of n, samples.size() == 3 * sample_width *
// sample_height. Returns (sample_width / n) x (sample_height / n) RGB pixels, rows bottom to top.
std::vector<float> box_filter_rgb(std::span<const float> samples, int sample_width,
                                  int sample_height, int n);

}  // namespace relief
