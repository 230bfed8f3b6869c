// How far the ground truth is from converged (relief reference --converge; docs/ground-truth.md,
// "Convergence"): the same frame rendered again at twice its settings (twice the samples a
// pixel each way, twice the grid each way, half the octave threshold) and the difference of the
// two measured like any error (image_error.h: mean LDR-FLIP, PSNR of the display values), over
// the whole image and per band of distance: the sky (pixels most of whose samples see no
// terrain), and the terrain's pixels in thirds by their distance from the camera (near, middle
// and far: the far third holds the rows just below the skyline, where the truth has been the
// least trustworthy).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eval/flip.h"
#include "eval/ground_truth.h"

namespace relief {

// Twice `settings`: supersample and grid_scale doubled, octave_epsilon halved, band_rows 0.
GroundTruthSettings doubled_settings(const GroundTruthSettings& settings);

// Throws GroundTruthError unless `settings` and twice them are in range for `scene`
// (validate_ground_truth): the message names the option, the value given and the range that
// leaves room to double it.
void validate_convergence(const Scene& scene, const GroundTruthSettings& settings);

// Per pixel of `image` (rendered with distances): 0 sky, 1 near, 2 middle, 3 far. The terrain
// pixels are ranked by distance (ties by index) and cut into three runs of equal count (the
// remainder to the near ones).
inline constexpr int kDistanceBands = 4;
inline constexpr const char* kDistanceBandNames[kDistanceBands] = {"sky", "near third",
                                                                   "middle third", "far third"};
std::vector<int> distance_bands(const GroundTruthImage& image);

struct BandError {
  std::string band;
  std::size_t pixels = 0;
  double mean_flip = 0;  // 0 for a band without pixels
  double psnr_db = 0;    // +infinity where the display values agree
  // The largest distance of the band's pixels from the camera (0 for the sky).
  double max_distance = 0;
};

struct ConvergenceReport {
  GroundTruthSettings settings, doubled;
  BandError all;
  std::vector<BandError> bands;  // kDistanceBandNames's order
};

// The error of `test` against `reference` (linear RGB of the same size as `banded_by`), over
// the image and per band of `banded_by`'s distances (kDistanceBandNames's order).
struct BandedError {
  BandError all;
  std::vector<BandError> bands;
};
BandedError banded_error(std::span<const float> test, std::span<const float> reference,
                         const GroundTruthImage& banded_by,
                         double pixels_per_degree = kDefaultPixelsPerDegree);

// How much the picture changes from `before` to `after` (linear RGB, the size of `banded_by`):
// per band of `banded_by`'s distances and then over the image (kDistanceBands + 1 values), the
// mean over pixels of the mean over channels of |after - before| in sRGB codes (0 to 255) of
// the display values; 0 for a band without pixels.
std::vector<double> banded_change(std::span<const float> before, std::span<const float> after,
                                  const GroundTruthImage& banded_by);

// The difference of `base` (rendered with distances) and `doubled` (the same scene at
// doubled_settings), per band of `base`'s distances. Precondition: the two are the same size.
ConvergenceReport compare_truths(const GroundTruthImage& base, const GroundTruthImage& doubled,
                                 const GroundTruthSettings& settings,
                                 double pixels_per_degree = kDefaultPixelsPerDegree);

}  // namespace relief
