// LDR-FLIP, the perceptual difference of two images as a person sees them flipped between on a
// display (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2),
// 2020), implemented from the published formulation (docs/ground-truth.md, "FLIP"):
//
//   colour: both images to YCxCz; each channel filtered with its contrast sensitivity function
//     (§3.1: sums of Gaussians in visual degrees, radius 3 sigma of the widest); back to linear
//     RGB, clamped to [0, 1]; to L*a*b* with the Hunt adjustment (a, b scaled by 0.01 L);
//     HyAB distance raised to qc = 0.7, mapped to [0, 1] by the compressed curve of §3.2
//     (pc = 0.4, pt = 0.95 of cmax, the Hunt-adjusted HyAB distance of green to blue);
//   features: edges and points of the achromatic channel Y / Y_white (first and second
//     Gaussian derivatives, sd = 0.5 w ppd with w = 0.082 degrees, positive and negative
//     weights each normalised to one), their magnitude difference over sqrt 2, raised to
//     qf = 0.5;
//   FLIP = colour error ^ (1 - feature error), per pixel, in [0, 1].
//
// Borders are clamped to the edge (every filter). Computed in double in one thread, in a fixed
// order: the same bits on every run.
#pragma once

#include <span>
#include <vector>

namespace relief {

// The viewing set-up of the default: a 0.7 m wide monitor of 3840 pixels seen from 0.7 m, the
// FLIP paper's and its reference implementation's: 0.7 * 3840 / 0.7 * pi / 180 = 67.02 pixels
// per degree.
inline constexpr double kDefaultPixelsPerDegree =
    0.7 * 3840.0 / 0.7 * 3.14159265358979323846 / 180.0;
// The filters' radii grow with the pixels per degree (about 0.15 ppd): 1000 makes 300-tap
// filters, beyond any display; below 1 a pixel spans more than a degree.
inline constexpr double kMinPixelsPerDegree = 1.0;
inline constexpr double kMaxPixelsPerDegree = 1000.0;

// Pixels per degree of a display `width_m` wide with `width_px` pixels seen from `distance_m`.
double pixels_per_degree(double distance_m, double width_m, int width_px);

// Per-pixel LDR-FLIP of `test` against `reference`: linear RGB, width * height * 3 values each,
// rows in the same order in both (the map comes out in that order). Values are clamped to
// [0, 1] first (an LDR display; NaN counts as 0). Precondition: width, height >= 1,
// pixels_per_degree in [kMinPixelsPerDegree, kMaxPixelsPerDegree].
std::vector<float> flip_error_map(std::span<const float> test, std::span<const float> reference,
                                  int width, int height, double pixels_per_degree);

}  // namespace relief
