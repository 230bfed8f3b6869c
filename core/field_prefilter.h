// Samples that the cubic B-spline passes through: terrain.heightfield.interpolating.
//
// The sketch's surface is the uniform cubic B-spline of its stored values (core/height_sketch.h),
// which approximates them: at a texel centre it is (c[i-1] + 4 c[i] + c[i+1]) / 6 along each
// axis, taps clamped to the edge. Real elevation data and exported maps hold point heights the
// surface should pass through, so the loader may store instead the coefficients c that solve
//   (c[i-1] + 4 c[i] + c[i+1]) / 6 = v[i],   c[-1] = c[0], c[n] = c[n-1]
// along every row, then along every column (the tensor product separates): the interpolating
// cubic B-spline (Unser, Aldroubi & Eden 1991, "Fast B-spline transforms"), here with
// GL_CLAMP_TO_EDGE's boundary instead of a mirror. The system is tridiagonal with diagonal
// 4 (5 at both ends) and off-diagonals 1, strictly diagonally dominant: Gaussian elimination
// without pivoting (the Thomas algorithm) is stable, every pivot lies in [2 + sqrt 3, 5].
// Coefficients may overshoot the samples' range: along one axis a checkerboard's coefficients
// are 3 times its half-range from its middle, 9 times in both (the loader refuses coefficients
// beyond +-1e7); the height bounds stay exact, being the coefficients' extremes.
#pragma once

#include <span>

namespace relief {

// Replaces the width x height values (row j at j * width) by their interpolating coefficients,
// in double, rounded once per pass to float. Precondition: width, height >= 2, every value
// finite. Outputs are finite (each is a bounded linear combination of the inputs; the caller
// checks their range).
void interpolating_coefficients(std::span<float> values, int width, int height);

}  // namespace relief
