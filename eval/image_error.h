// The error of a render against a reference (relief error, and relief sweep's figures;
// docs/ground-truth.md, "Error"): both given as linear radiance, RGB floats, the same size and
// row order. Figures on the display's values: each channel clamped to [0, 1] (NaN as 0) and
// sRGB-encoded (core/srgb.h), so that an 8-bit PNG of a linear image is compared where its
// quantisation is uniform:
//   RMSE = sqrt(mean over pixels and channels of (t - r)^2), max = the largest |t - r|,
//   PSNR = 20 log10(1 / RMSE) dB (peak 1; infinite for RMSE = 0);
// and LDR-FLIP (flip.h): its per-pixel map and mean.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "eval/flip.h"

namespace relief {

// A linear channel's display value: clamped to [0, 1] (NaN as 0), sRGB-encoded.
double display_value(float linear);

struct ImageError {
  double rmse = 0;
  double psnr_db = 0;  // +infinity when rmse == 0
  double max_error = 0;
  std::size_t max_pixel = 0;  // index of a pixel with the largest difference (the first)
  int max_channel = 0;
  double mean_flip = 0;
  std::vector<float> flip_map;  // per pixel, in [0, 1]
};

// Precondition: test.size() == reference.size() == 3 * width * height, width, height >= 1,
// pixels_per_degree in [kMinPixelsPerDegree, kMaxPixelsPerDegree].
ImageError image_error(std::span<const float> test, std::span<const float> reference, int width,
                       int height, double pixels_per_degree = kDefaultPixelsPerDegree);

// Bytes image_error holds at its peak for a width x height image (the caller's inputs apart):
// FLIP's double planes and the map.
std::size_t image_error_bytes(int width, int height);

}  // namespace relief
